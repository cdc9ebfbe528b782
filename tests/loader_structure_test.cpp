// The loader: faces and indices, materials, defaults and structure, the camera, textures, files.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include "rayview/scene_loader.h"
#include "support/loader_scenes.h"
#include "support/test_directory.h"

namespace rayview {
namespace {

using namespace loader_testing;
namespace fs = std::filesystem;

// ---------------------------------------------------------------- faces and indices

TEST(Loader, ZeroBasedFacesAreDetectedWithOneWarning) {
  const std::string xml = with("1 2 3\n1 3 4\n", "0 1 2\n0 2 3\n");
  const LoadedScene loaded = load(xml);
  EXPECT_TRUE(hasWarning(loaded, 38, "face indices are 0-based (vertex indices include 0 and never reach the count)"));
  EXPECT_EQ(loaded.warnings.size(), 1u);
  ASSERT_EQ(loaded.scene.triangles.size(), 2u);
  EXPECT_EQ(loaded.scene.triangles[1].vertex[0], 0u);
  EXPECT_EQ(loaded.scene.triangles[1].vertex[2], 3u);
  expectError(xml, 38, "face indices are 0-based", strictOptions());
}

TEST(Loader, ZeroBasedDecisionIsPerFileOverAllMeshes) {
  // Mesh 1 alone looks 1-based (no 0), mesh 2 has a 0: the file is 0-based, so mesh 1's 3 is vertex 3 (0-based).
  const std::string second = "<mesh id=\"b\"><materialid>red</materialid><faces>0 1 2</faces></mesh>";
  const std::string xml = with("</objects>", second + "</objects>", with("1 2 3\n1 3 4\n", "1 2 3\n1 3 2\n"));
  const LoadedScene loaded = load(xml);
  EXPECT_TRUE(hasWarning(loaded, 42, "0-based"));
  ASSERT_EQ(loaded.scene.triangles.size(), 3u);
  EXPECT_EQ(loaded.scene.triangles[0].vertex[2], 3u);
  EXPECT_EQ(loaded.scene.meshes.at(1).id, "b");
  EXPECT_EQ(loaded.scene.meshOf(2), 1u);
}

// Plain faces hold no attributes; once one face has them, every triangle has its entry, kept in step with the
// triangles when degenerate faces are dropped.
TEST(Loader, FaceAttributesAreHeldOnlyWhenAFaceHasThemAndStayInStep) {
  EXPECT_TRUE(load(kBase).scene.faceAttributes.empty());
  const std::string second =
      "<mesh id=\"n\"><materialid>red</materialid><faces>1//1 1//1 2//1\n2//1 3//1 4//1\n</faces></mesh>";
  const LoadedScene loaded = load(with("</objects>", second + "</objects>",
                                       with("</vertexdata>\n", "</vertexdata><normaldata>0 0 1</normaldata>\n")));
  ASSERT_EQ(loaded.scene.triangles.size(), 3u);  // the repeated-vertex face is dropped
  ASSERT_EQ(loaded.scene.faceAttributes.size(), 3u);
  EXPECT_FALSE(loaded.scene.attributesOf(0).any());
  EXPECT_FALSE(loaded.scene.attributesOf(1).any());
  EXPECT_EQ(loaded.scene.triangles[2].vertex[0], 1u);
  EXPECT_TRUE(loaded.scene.attributesOf(2).hasNormals());
  EXPECT_EQ(loaded.scene.attributesOf(2).normal[2], 0);
  EXPECT_EQ(loaded.scene.meshOf(2), 1u);
  EXPECT_EQ(loaded.scene.materialOf(2), loaded.scene.meshes[1].material);
}

TEST(Loader, IndexOutOfRangeIsAnErrorAtTheFaceLine) {
  expectError(with("1 3 4\n", "1 3 5\n"), 39,
              "mesh \"quad\": vertex index 5 is out of range (the file has 4 vertices, indices 1..4)");
  // 0 and 4 both occur: neither 0-based nor 1-based.
  expectError(with("1 2 3\n1 3 4\n", "1 2 3\n0 3 4\n"), 39, "mesh \"quad\": vertex index 0 is out of range");
  // A 0 with an index past the count: 1-based, and the first 0 is the error.
  expectError(with("1 2 3\n1 3 4\n", "0 1 2\n0 2 9\n"), 38, "vertex index 0 is out of range (the file has 4 vertices, indices 1..4)");
  // Texture indices decide on their own: 0-based texture indices with 1-based vertices.
  const LoadedScene mixed = load(with("1 2 3\n1 3 4\n", "1/0 2/1 3/2\n1/0 3/2 4/3\n",
                                      with("</vertexdata>\n", "</vertexdata><texturedata>0 0 1 0 1 1 0 1</texturedata>\n")));
  EXPECT_TRUE(hasWarning(mixed, 38, "face indices are 0-based (texture indices include 0"));
  EXPECT_EQ(mixed.scene.attributesOf(1).texCoord[2], 3);
  EXPECT_EQ(mixed.scene.triangles.at(1).vertex[2], 3u);
}

TEST(Loader, FaceTokenErrors) {
  expectError(with("1 3 4\n", "1 3\n"), 37, "mesh \"quad\": <faces> has 5 vertex indices, not a multiple of 3");
  expectError(with("1 3 4\n", "1 -3 4\n"), 39, "face indices must be positive, found '-3'");
  expectError(with("1 3 4\n", "1 3 x\n"), 39, "expected a vertex index (v, v/t, v//n or v/t/n), found 'x'");
  expectError(with("1 3 4\n", "1 3 4/\n"), 39, "found '4/'");
  expectError(with("1 3 4\n", "1 3 4.0\n"), 39, "found '4.0'");
}

TEST(Loader, ObjStyleFaceTokens) {
  const std::string data =
      "</vertexdata><texturedata>0 0 1 0 1 1 0 1</texturedata><normaldata>0 0 1 0 0 -1</normaldata>";
  std::string xml = with("</vertexdata>\n", data + "\n");
  xml = with("1 2 3\n1 3 4\n", "1/1/2 2/2/2 3/3/2\n1//1 3//1 4//1\n", xml);
  const LoadedScene loaded = load(xml);
  EXPECT_TRUE(loaded.warnings.empty());
  ASSERT_EQ(loaded.scene.triangles.size(), 2u);
  ASSERT_EQ(loaded.scene.faceAttributes.size(), 2u);
  const FaceAttributes& a = loaded.scene.attributesOf(0);
  EXPECT_TRUE(a.hasTexCoords());
  EXPECT_TRUE(a.hasNormals());
  EXPECT_EQ(a.texCoord[2], 2);
  EXPECT_EQ(a.normal[0], 1);
  const FaceAttributes& b = loaded.scene.attributesOf(1);
  EXPECT_FALSE(b.hasTexCoords());
  EXPECT_EQ(b.normal[1], 0);
  EXPECT_EQ(loaded.scene.texCoords.at(2), glm::vec2(1, 1));

  const LoadedScene vt = load(with("1 2 3\n1 3 4\n", "1/1 2/2 3/3\n1/1 3/3 4/4\n", with("</vertexdata>\n", data + "\n")));
  EXPECT_TRUE(vt.scene.attributesOf(1).hasTexCoords());
  EXPECT_FALSE(vt.scene.attributesOf(1).hasNormals());
  EXPECT_EQ(vt.scene.attributesOf(1).texCoord[2], 3);

  expectError(with("1 2 3\n1 3 4\n", "1/1/1 2/2/1 3/3/1\n1/5/1 3/3/1 4/4/1\n", with("</vertexdata>\n", data + "\n")), 39,
              "texture index 5 is out of range (the file has 4 <texturedata> coordinates, indices 1..4)");
  expectError(with("1 2 3\n1 3 4\n", "1//1 2//1 3//1\n"), 38, "normal index 1 is out of range (the file has no <normaldata> normals)");
  expectError(with("1 2 3\n1 3 4\n", "1/1/1 2 3/3/1\n", with("</vertexdata>\n", data + "\n")), 38,
              "a face mixes index forms");
}

TEST(Loader, DegenerateTrianglesAreSkippedWithOneWarningPerMesh) {
  const std::string xml = with("1 2 3\n1 3 4\n", "1 2 3\n1 1 3\n2 2 2\n");
  const LoadedScene loaded = load(xml, strictOptions());  // not a repair: a warning even in strict mode
  EXPECT_TRUE(hasWarning(loaded, 35, "mesh \"quad\": 2 degenerate triangles skipped (zero area or a repeated vertex)"));
  ASSERT_EQ(loaded.scene.triangles.size(), 1u);
  EXPECT_EQ(loaded.scene.meshes[0].triangleCount, 1u);
  // Zero area from collinear points.
  const LoadedScene collinear = load(with("-1 1 -2\n", "0 0 -2\n", with("1 2 3\n1 3 4\n", "1 2 3\n1 3 4\n")));
  EXPECT_TRUE(hasWarning(collinear, 35, "1 degenerate triangle skipped"));
  EXPECT_EQ(collinear.scene.triangles.size(), 1u);
}

TEST(Loader, RepeatedFacesAreKeptWithOneWarning) {
  // The second quad repeats both faces, one of them with the opposite winding.
  const LoadedScene loaded = load(with("1 2 3\n1 3 4\n", "1 2 3\n1 3 4\n3 2 1\n4 3 1\n"), strictOptions());
  EXPECT_TRUE(hasWarning(loaded, 35, "2 faces repeat the three vertices of an earlier face (the first in mesh \"quad\")"));
  EXPECT_EQ(loaded.scene.triangles.size(), 4u);  // kept: which one is seen is the renderer's tie rule
  EXPECT_TRUE(load(with("1 2 3\n1 3 4\n", "1 2 3\n1 3 4\n")).warnings.empty());
}

TEST(Loader, RepeatedFacesAreNamedByTheEarliestRepeat) {
  // The first repeat is in mesh "b" (a rotation of quad's first face); mesh "c", after it, repeats quad's second.
  const std::string more = "<mesh id=\"b\"><materialid>red</materialid><faces>3 1 2</faces></mesh>\n"
                           "<mesh id=\"c\"><materialid>red</materialid><faces>4 3 1</faces></mesh>";
  const LoadedScene loaded = load(with("</objects>", more + "</objects>"));
  EXPECT_TRUE(hasWarning(loaded, 42, "2 faces repeat the three vertices of an earlier face (the first in mesh \"b\")"));
}

TEST(Loader, RepeatedFacesAreCountedExactlyInALargeMesh) {
  // A 60 x 60 grid's 6 962 triangles, then earlier faces again in other windings and orders (some twice, some
  // repeats of repeats): the count is the faces whose three vertices an earlier face has.
  constexpr int kSide = 60;
  std::string vertices;
  for (int y = 0; y < kSide; ++y)
    for (int x = 0; x < kSide; ++x) vertices += std::to_string(x) + " " + std::to_string(y) + " -2\n";
  std::vector<std::array<int, 3>> faces;
  for (int y = 0; y + 1 < kSide; ++y)
    for (int x = 0; x + 1 < kSide; ++x) {
      const int a = y * kSide + x + 1, b = a + 1, c = a + kSide, d = c + 1;
      faces.push_back({a, b, d});
      faces.push_back({a, d, c});
    }
  const std::size_t unique = faces.size();
  std::uint32_t state = 12345;
  auto next = [&] { return state = state * 1664525u + 1013904223u; };
  for (int k = 0; k < 500; ++k) {
    std::array<int, 3> f = faces[next() % faces.size()];  // may pick a repeat: a repeat of a repeat
    std::rotate(f.begin(), f.begin() + next() % 3, f.end());
    if (next() % 2) std::swap(f[1], f[2]);
    faces.push_back(f);
  }
  std::string text;
  for (const auto& f : faces) text += std::to_string(f[0]) + " " + std::to_string(f[1]) + " " + std::to_string(f[2]) + "\n";
  const LoadedScene loaded = load(with("1 2 3\n1 3 4\n", text, with("-1 -1 -2\n1 -1 -2\n1 1 -2\n-1 1 -2\n", vertices)));
  ASSERT_EQ(loaded.scene.triangles.size(), faces.size());
  EXPECT_EQ(unique, 6962u);
  EXPECT_TRUE(hasWarning(loaded, 35 + kSide * kSide - 4,
                         "500 faces repeat the three vertices of an earlier face (the first in mesh \"quad\")"));
}

// ---------------------------------------------------------------- materials

TEST(Loader, MaterialIdsAreStringsAndMustResolve) {
  expectError(with("<materialid>red</materialid>", "<materialid>blue</materialid>"), 36,
              "mesh \"quad\": material \"blue\" is not defined (defined: \"red\")");
  expectError(with("</materials>", "<material id=\"red\"><ambient>0 0 0</ambient></material></materials>"), 27,
              "duplicate material id \"red\" (the first is at line 20)");
  expectError(with("<material id=\"red\">", "<material>"), 20, "<material> has no id attribute");
  expectError(with("<diffuse>1 0 0</diffuse>", ""), 20, "<material id=\"red\"> has no <diffuse>");
  expectError(with("<materialid>red</materialid>", ""), 35, "<mesh id=\"quad\"> has no <materialid>");
  EXPECT_EQ(load(with("<materialid>red</materialid>", "<materialid> red </materialid>")).scene.triangles.size(), 2u);
}

TEST(Loader, MaterialOptionalParts) {
  const LoadedScene noMirror = load(with("<mirrorreflectance>0 0 0</mirrorreflectance>", ""));
  EXPECT_TRUE(hasWarning(noMirror, 20, "<material id=\"red\"> has no <mirrorreflectance>; using 0 0 0"));
  const LoadedScene factor = load(with("<phongexponent>1</phongexponent>", "<phongexponent>1</phongexponent><texturefactor>0.25</texturefactor>"));
  EXPECT_EQ(factor.scene.materials[0].textureFactor, 0.25f);
  EXPECT_FALSE(factor.scene.materials[0].twoSided);
  const LoadedScene twoSided = load(with("<phongexponent>1</phongexponent>", "<phongexponent>1</phongexponent><twosided>1</twosided>"));
  EXPECT_TRUE(twoSided.scene.materials[0].twoSided);
  EXPECT_FALSE(load(with("<phongexponent>1</phongexponent>", "<phongexponent>1</phongexponent><twosided> 0 </twosided>"))
                   .scene.materials[0].twoSided);
  expectError(with("<phongexponent>1</phongexponent>", "<phongexponent>1</phongexponent><twosided>2</twosided>"), 24,
              "<twosided>: expected 0 or 1");
  expectError(with("<phongexponent>1</phongexponent>", "<phongexponent>1</phongexponent><twosided>yes</twosided>"), 24,
              "<twosided>: expected 0 or 1");
  expectError(with("<phongexponent>1</phongexponent>", "<phongexponent>-2</phongexponent>"), 24, "<phongexponent>: must be >= 0");
}

// ---------------------------------------------------------------- defaults and structure

TEST(Loader, MissingOptionalElementsTakeDefaultsWithWarnings) {
  std::string xml = with("<maxraytracedepth>1</maxraytracedepth>", "");
  xml = with("<background>1 2 3</background>", "", xml);
  xml = with("<ambientlight>5 5 5</ambientlight>", "", xml);
  const LoadedScene loaded = load(xml, strictOptions());
  EXPECT_TRUE(hasWarning(loaded, 1, "no <maxraytracedepth>: using 0"));
  EXPECT_TRUE(hasWarning(loaded, 1, "no <background>: using black (0 0 0)"));
  EXPECT_TRUE(hasWarning(loaded, 1, "no <ambientlight>: using black (0 0 0)"));
  EXPECT_EQ(loaded.scene.maxRayDepth, 0);
  EXPECT_EQ(loaded.scene.background, Color(0));
  EXPECT_EQ(loaded.scene.ambientLight, Color(0));
}

TEST(Loader, MissingOrDuplicateRequiredElementsAreErrors) {
  const std::size_t begin = kBase.find("<camera>"), end = kBase.find("</camera>\n") + 10;
  std::string noCamera = kBase;
  noCamera.replace(begin, end - begin, "");
  expectError(noCamera, 1, "no <camera> element");
  expectError(with("<up>0 1 0</up>", ""), 4, "<camera> has no <up>");
  expectError(with("<intensity>100 100 100</intensity>", ""), 14, "<pointlight id=\"1\"> has no <intensity>");
  expectError(with("</camera>", "<gaze>0 0 1</gaze></camera>"), 11, "duplicate <gaze> inside <camera> (the first is at line 6)");
  expectError(with("<background>1 2 3</background>", "<background>1 2 3</background><background>0 0 0</background>"), 3,
              "duplicate <background> inside <scene>");
}

TEST(Loader, UnknownElementsAndStrayTextAreWarnings) {
  std::string xml = with("</camera>", "<fov>60</fov></camera>");
  xml = with("</objects>", "<sphere id=\"s\"><center>0 0 0</center></sphere>\n...\n</objects>", xml);
  const LoadedScene loaded = load(xml);
  EXPECT_TRUE(hasWarning(loaded, 11, "unknown element <fov> ignored"));
  EXPECT_TRUE(hasWarning(loaded, 42, "unknown element <sphere> ignored (only <mesh> objects are part of the format)"));
  EXPECT_TRUE(hasWarning(loaded, 43, "stray text '...' ignored"));
  EXPECT_EQ(loaded.scene.triangles.size(), 2u);
  expectError(xml, 11, "unknown element <fov> ignored", strictOptions());
  expectError(with("</objects>", "\n...\n</objects>"), 43, "stray text '...'", strictOptions());
  // A known element in the wrong place.
  const LoadedScene misplaced = load(with("</lights>", "<gaze>1 1 1</gaze></lights>"));
  EXPECT_TRUE(hasWarning(misplaced, 18, "element <gaze> is not expected inside <lights>; ignored"));
}

TEST(Loader, WrongRootOrEmptyFile) {
  expectError("", 0, "no <scene> element");
  expectError("  \n  ", 0, "no <scene> element");
  expectError("<!-- nothing -->\n", 0, "no <scene> element");
  expectError("<world>\n</world>\n", 1, "the root element is <world>, expected <scene>");
}

TEST(Loader, Ceng477ScenesAreRecognised) {
  const std::string ceng =
      "<Scene>\n<BackgroundColor>0 0 0</BackgroundColor>\n<MaxRecursionDepth>6</MaxRecursionDepth>\n"
      "<Cameras>\n<Camera id=\"1\"><Position>0 0 0</Position></Camera>\n</Cameras>\n</Scene>\n";
  // Read as the CENG477 dialect (tests/ceng477_dialect_test.cpp), in its own names.
  expectError(ceng, 5, "<Camera> has no <Gaze>");
}

// ---------------------------------------------------------------- camera (SPEC section 3)

TEST(Loader, CameraValidity) {
  struct Case {
    std::string from, to, message;
  };
  const Case cases[] = {
      {"<gaze>0 0 -1</gaze>", "<gaze>0 0 0</gaze>", "camera: <gaze> is the zero vector"},
      {"<up>0 1 0</up>", "<up>0 0 2</up>", "camera: <up> is parallel to <gaze>"},
      {"<up>0 1 0</up>", "<up>0 0 0</up>", "camera: <up> is the zero vector"},
      {"<nearplane>-1 1 -1 1</nearplane>", "<nearplane>1 1 -1 1</nearplane>", "camera: <nearplane> left and right are equal (1)"},
      {"<nearplane>-1 1 -1 1</nearplane>", "<nearplane>-1 1 2 2</nearplane>", "camera: <nearplane> bottom and top are equal (2)"},
      {"<neardistance>1</neardistance>", "<neardistance>0</neardistance>", "camera: <neardistance> must be positive, found 0"},
      {"<neardistance>1</neardistance>", "<neardistance>-1</neardistance>", "camera: <neardistance> must be positive, found -1"},
      {"<imageresolution>4 3</imageresolution>", "<imageresolution>0 3</imageresolution>", "camera: <imageresolution> must be positive, found 0 x 3"},
      {"<imageresolution>4 3</imageresolution>", "<imageresolution>4 -3</imageresolution>", "camera: <imageresolution> must be positive, found 4 x -3"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.to);
    expectError(with(c.from, c.to), 4, c.message);
  }
  // A slightly tilted up vector is fine (re-orthogonalised by the camera).
  EXPECT_NO_THROW(load(with("<up>0 1 0</up>", "<up>0 1 0.1</up>")));
}

TEST(Loader, HugeImagesAreRefusedUpFront) {
  expectError(with("<imageresolution>4 3</imageresolution>", "<imageresolution>200000 200000</imageresolution>"), 10,
              "<imageresolution>: 200000 x 200000 pixels is too large (the limit is 268435456 pixels");
  expectError(with("<imageresolution>4 3</imageresolution>", "<imageresolution>3000000000 1</imageresolution>"), 10,
              "is too large");
  expectError(with("<imageresolution>4 3</imageresolution>", "<imageresolution>99999999999999999999999 1</imageresolution>"), 10,
              "<imageresolution>: expected 2 integers (nx ny), found '99999999999999999999999'");
  EXPECT_EQ(load(with("<imageresolution>4 3</imageresolution>", "<imageresolution>16384 16384</imageresolution>")).scene.camera.width, 16384);
}

TEST(Loader, ShadowRayEpsilonExtension) {
  const std::string xml = with("<background>1 2 3</background>", "<background>1 2 3</background><shadowrayepsilon>1e-3</shadowrayepsilon>");
  const LoadedScene loaded = load(xml, strictOptions());
  ASSERT_TRUE(loaded.scene.shadowRayEpsilon.has_value());
  EXPECT_DOUBLE_EQ(*loaded.scene.shadowRayEpsilon, 1e-3);
  expectError(with("<background>1 2 3</background>", "<background>1 2 3</background><shadowrayepsilon>-1</shadowrayepsilon>"), 3,
              "<shadowrayepsilon>: must be >= 0");
}

// ---------------------------------------------------------------- textures

class LoaderTexture : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = testing::freshTestDirectory("rayview_loader_test");
    fs::create_directories(dir_ / "repo" / "assets" / "scenes");
    fs::create_directories(dir_ / "repo" / "assets" / "textures");
    // A 2 x 1 binary PPM: red, green.
    std::ofstream(dir_ / "repo" / "assets" / "textures" / "t.ppm", std::ios::binary)
        << "P6\n2 1\n255\n" << std::string("\xff\x00\x00\x00\xff\x00", 6);
  }
  void TearDown() override { fs::remove_all(dir_); }

  LoadedScene loadIn(const std::string& texture, const LoadOptions& options = {}) {
    const fs::path scene = dir_ / "repo" / "assets" / "scenes" / "s.xml";
    std::ofstream(scene) << with("</objects>\n", "</objects>\n<textureimage>" + texture + "</textureimage>\n");
    return loadSceneFile(scene, options);
  }
  fs::path dir_;
};

TEST_F(LoaderTexture, RelativeToAnAncestorOfTheSceneDirectory) {
  const LoadedScene loaded = loadIn("./assets/textures/t.ppm");
  EXPECT_TRUE(loaded.warnings.empty());
  ASSERT_TRUE(loaded.scene.texture.has_value());
  EXPECT_EQ(loaded.scene.texture->width, 2);
  EXPECT_EQ(loaded.scene.texture->height, 1);
  ASSERT_EQ(loaded.scene.texture->rgb.size(), 6u);
  EXPECT_EQ(loaded.scene.texture->rgb[0], 255);
  EXPECT_EQ(loaded.scene.texture->rgb[4], 255);
  EXPECT_EQ(loaded.scene.textureImage, "./assets/textures/t.ppm");
  EXPECT_EQ(loaded.scene.sourcePath.filename(), "s.xml");
}

TEST_F(LoaderTexture, AbsolutePathFromAnotherMachineFallsBackToItsTail) {
  const LoadedScene loaded = loadIn("/home/someone/hw1/textures/t.ppm");
  EXPECT_TRUE(loaded.scene.texture.has_value());
}

TEST_F(LoaderTexture, MissingTextureIsAWarningNamingThePathsTried) {
  const LoadedScene loaded = loadIn("nowhere.png");
  EXPECT_FALSE(loaded.scene.texture.has_value());
  ASSERT_EQ(loaded.warnings.size(), 1u);
  const Diagnostic& w = loaded.warnings[0];
  EXPECT_EQ(w.where.line, 43);
  EXPECT_NE(w.message.find("texture image \"nowhere.png\" could not be read (tried "), std::string::npos) << w.message;
  EXPECT_NE(w.message.find((dir_ / "repo" / "assets" / "scenes" / "nowhere.png").string()), std::string::npos) << w.message;
  EXPECT_NE(w.message.find("rendering without the texture"), std::string::npos);
}

TEST_F(LoaderTexture, UnreadableTextureIsAWarning) {
  std::ofstream(dir_ / "repo" / "assets" / "scenes" / "bad.png") << "not an image";
  const LoadedScene loaded = loadIn("bad.png");
  EXPECT_FALSE(loaded.scene.texture.has_value());
  ASSERT_EQ(loaded.warnings.size(), 1u);
  EXPECT_NE(loaded.warnings[0].message.find("bad.png: not a readable image"), std::string::npos) << loaded.warnings[0].message;
}

TEST_F(LoaderTexture, NotLoadedWhenAskedNotTo) {
  LoadOptions options;
  options.loadTexture = false;
  const LoadedScene loaded = loadIn("nowhere.png", options);
  EXPECT_TRUE(loaded.warnings.empty());
  EXPECT_FALSE(loaded.scene.texture.has_value());
  EXPECT_EQ(loaded.scene.textureImage, "nowhere.png");
}

// loadSceneFile lets tinyxml2 read a file the repair pass leaves unchanged itself (one copy of the text at the
// parse, not two); whatever it reads, the scene, the warnings and every message are those of the same text loaded
// from memory.
TEST(LoaderFile, AFileLoadsAsItsTextDoesWithTheSameMessages) {
  const fs::path path = fs::temp_directory_path() /
                        ("rayview_loader_file_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) + ".xml");
  auto message = [](auto load) {
    try {
      const LoadedScene loaded = load();
      std::string summary = "ok " + std::to_string(loaded.scene.triangles.size()) + " triangles";
      for (const Diagnostic& d : loaded.warnings) summary += "; " + d.message;
      return summary;
    } catch (const SceneError& e) {
      return std::string(e.what());
    }
  };
  const std::vector<std::string> texts = {
      kBase,                                             // loads
      with("</objects>", "</objects><unknown/>"),        // a warning
      with("<camera>", "<camera a=\"1\" a=\"2\">"),  // an XML error tinyxml2 finds
      kBase + "<!-- never closed",                      // another
      "<!-- nothing but a comment -->",                  // no element
      "plain text, no markup at all\n",                 // not XML
      "",                                                // empty
  };
  for (const std::string& text : texts) {
    std::ofstream(path, std::ios::binary | std::ios::trunc) << text;
    const std::string fromFile = message([&] { return loadSceneFile(path); });
    std::string fromText = message([&] { return loadSceneText(text, path.string(), path.parent_path()); });
    EXPECT_EQ(fromFile, fromText) << text.substr(0, 60);
  }
  fs::remove(path);
}

TEST(LoaderFile, MissingFileIsAnErrorNamingIt) {
  try {
    loadSceneFile("/nonexistent/dir/scene.xml");
    FAIL() << "loaded";
  } catch (const SceneError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("/nonexistent/dir/scene.xml: error: cannot open the scene file", 0), 0u) << e.what();
  }
  EXPECT_THROW(loadSceneFile(fs::temp_directory_path()), SceneError);
}

// A triangle's mesh (and material) is the range that holds it, whatever empty meshes lie around it.
TEST(SceneGeometry, EachTriangleBelongsToTheMeshRangeThatHoldsIt) {
  SceneGeometry g;
  g.triangles.resize(3);
  g.meshes = {Mesh{"empty-first", 7, 0, 0}, Mesh{"b", 1, 0, 2}, Mesh{"empty-middle", 8, 2, 0}, Mesh{"d", 2, 2, 1},
              Mesh{"empty-last", 9, 3, 0}};
  EXPECT_EQ(g.meshOf(0), 1u);
  EXPECT_EQ(g.meshOf(1), 1u);
  EXPECT_EQ(g.meshOf(2), 3u);
  EXPECT_EQ(g.materialOf(1), 1u);
  EXPECT_EQ(g.materialOf(2), 2u);
  EXPECT_EQ(SceneGeometry{}.materialOf(0), 0u);  // no meshes: material 0, never out of bounds

  // The branch-free search against a plain scan, on every size up to 40 with repeated starts.
  for (std::size_t count = 1; count <= 40; ++count) {
    std::vector<std::uint32_t> starts(count);
    for (std::size_t k = 1; k < count; ++k) starts[k] = starts[k - 1] + static_cast<std::uint32_t>((k * 7) % 3);
    for (std::uint32_t t = 0; t <= starts.back() + 2; ++t) {
      std::size_t expected = 0;
      for (std::size_t k = 0; k < count; ++k)
        if (starts[k] <= t) expected = k;
      EXPECT_EQ(lastRangeAtOrBefore(count, t, [&](std::size_t k) { return starts[k]; }), expected)
          << count << " ranges, triangle " << t;
    }
  }
}

// The check the tests and the fuzz targets share names what breaks a scene, and passes what loads.
TEST(SceneGeometry, WholenessProblemNamesWhatIsBroken) {
  Scene whole;
  whole.materials.resize(2);
  whole.vertices.resize(3);
  whole.triangles = {Triangle{{0, 1, 2}}, Triangle{{2, 1, 0}}, Triangle{{0, 2, 1}}};
  whole.meshes = {Mesh{"a", 0, 0, 2}, Mesh{"empty", 1, 2, 0}, Mesh{"c", 1, 2, 1}};
  EXPECT_EQ(wholenessProblem(whole), "");
  EXPECT_EQ(wholenessProblem(Scene{}), "");

  auto broken = [&](auto&& edit) {
    Scene s = whole;
    edit(s);
    return wholenessProblem(s);
  };
  EXPECT_NE(broken([](Scene& s) { s.meshes[2].firstTriangle = 1; }).find("does not start where"), std::string::npos);
  EXPECT_NE(broken([](Scene& s) { s.meshes[0].material = 2; }).find("no real material"), std::string::npos);
  EXPECT_NE(broken([](Scene& s) { s.meshes[2].triangleCount = 2; }).find("claims more triangles"), std::string::npos);
  EXPECT_NE(broken([](Scene& s) { s.meshes.pop_back(); }).find("do not cover"), std::string::npos);
  EXPECT_NE(broken([](Scene& s) { s.triangles[1].vertex[2] = 3; }).find("triangle 1: a vertex"), std::string::npos);
  EXPECT_NE(broken([](Scene& s) { s.faceAttributes.resize(2); }).find("not one per triangle"), std::string::npos);
  EXPECT_NE(broken([](Scene& s) {
              s.faceAttributes.resize(3);
              s.normals.resize(1);
              s.faceAttributes[2].normal[0] = s.faceAttributes[2].normal[1] = 0;
              s.faceAttributes[2].normal[2] = 1;
            }).find("triangle 2: a normal"),
            std::string::npos);
  EXPECT_NE(broken([](Scene& s) {
              s.texCoords.resize(1);
              s.faceAttributes.resize(3);
              s.faceAttributes[0].texCoord[0] = s.faceAttributes[0].texCoord[1] = 0;
              s.faceAttributes[0].texCoord[2] = 1;
            }).find("triangle 0: a texture coordinate"),
            std::string::npos);
}

// Parameters that come as bytes (the import worker's answer) are held to what the loader checks of each value: what
// it loads passes, and each value it would refuse is named.
TEST(SceneParameters, ParametersProblemRefusesWhatTheLoaderRefuses) {
  const Scene loaded = load(kBase).scene;
  EXPECT_EQ(parametersProblem(loaded), "");
  auto broken = [&](auto&& edit) {
    SceneParameters p = loaded;
    edit(p);
    return parametersProblem(p);
  };
  const double inf = std::numeric_limits<double>::infinity();
  const float nan = std::numeric_limits<float>::quiet_NaN();
  EXPECT_NE(broken([&](SceneParameters& p) { p.camera.position.x = inf; }).find("camera"), std::string::npos);
  EXPECT_NE(broken([](SceneParameters& p) { p.camera.up = p.camera.gaze; }).find("parallel"), std::string::npos);
  EXPECT_NE(broken([](SceneParameters& p) { p.camera.nearDistance = 0.0; }).find("near distance"), std::string::npos);
  EXPECT_NE(broken([](SceneParameters& p) { p.camera.width = 0; }).find("resolution"), std::string::npos);
  EXPECT_NE(broken([](SceneParameters& p) { p.maxRayDepth = -1; }).find("depth"), std::string::npos);
  EXPECT_NE(broken([](SceneParameters& p) { p.shadowRayEpsilon = -1.0; }).find("epsilon"), std::string::npos);
  EXPECT_NE(broken([&](SceneParameters& p) { p.ambientLight.y = nan; }).find("ambient"), std::string::npos);
  EXPECT_NE(broken([&](SceneParameters& p) { p.lights.of<PointLight>()[0].intensity.x = nan; }).find("light \""),
            std::string::npos);
  EXPECT_NE(broken([&](SceneParameters& p) { p.materials[0].diffuse.z = nan; }).find("not finite"), std::string::npos);
  EXPECT_NE(broken([](SceneParameters& p) { p.materials[0].phongExponent = -1.0f; }).find("Phong"), std::string::npos);
  EXPECT_NE(broken([](SceneParameters& p) { p.materials.push_back(p.materials[0]); }).find("used twice"),
            std::string::npos);
}

}  // namespace
}  // namespace rayview
