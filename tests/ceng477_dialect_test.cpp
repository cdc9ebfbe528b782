// The loader's CENG477 dialect (docs/scene-format.md, "The CENG477 dialect"): each mapping onto the scene, each
// message with its line, PLY faces from files the test writes, and the course's 16 conformance files, which must
// load into exactly the scene of their conversions to the CSE 461 format.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>

#include "rayview/frame_renderer.h"
#include "rayview/prepared_scene.h"
#include "rayview/scene_loader.h"
#include "rayview/scene_writer.h"
#include "support/image_compare.h"
#include "support/scene_compare.h"

namespace rayview {
namespace {

namespace fs = std::filesystem;

const std::string kBase =
    "<Scene>\n"                                                        // 1
    "<BackgroundColor>1 2 3</BackgroundColor>\n"                       // 2
    "<ShadowRayEpsilon>1e-4</ShadowRayEpsilon>\n"                      // 3
    "<MaxRecursionDepth>2</MaxRecursionDepth>\n"                       // 4
    "<Cameras>\n"                                                      // 5
    "<Camera id=\"1\">\n"                                              // 6
    "<Position>0 0 0</Position>\n"                                     // 7
    "<Gaze>0 0 -1</Gaze>\n"                                            // 8
    "<Up>0 1 0</Up>\n"                                                 // 9
    "<NearPlane>-1 1 -0.75 0.75</NearPlane>\n"                         // 10
    "<NearDistance>1</NearDistance>\n"                                 // 11
    "<ImageResolution>32 24</ImageResolution>\n"                       // 12
    "<ImageName>out.ppm</ImageName>\n"                                 // 13
    "</Camera>\n"                                                      // 14
    "</Cameras>\n"                                                     // 15
    "<Lights>\n"                                                       // 16
    "<AmbientLight>5 5 5</AmbientLight>\n"                             // 17
    "<PointLight id=\"1\">\n"                                          // 18
    "<Position>0 0 1</Position>\n"                                     // 19
    "<Intensity>100 100 100</Intensity>\n"                             // 20
    "</PointLight>\n"                                                  // 21
    "</Lights>\n"                                                      // 22
    "<Materials>\n"                                                    // 23
    "<Material id=\"1\">\n"                                            // 24
    "<AmbientReflectance>0.1 0.1 0.1</AmbientReflectance>\n"           // 25
    "<DiffuseReflectance>0.5 0.5 0.5</DiffuseReflectance>\n"           // 26
    "<SpecularReflectance>0.2 0.2 0.2</SpecularReflectance>\n"         // 27
    "<MirrorReflectance>0.3 0.3 0.3</MirrorReflectance>\n"             // 28
    "<PhongExponent>10</PhongExponent>\n"                              // 29
    "</Material>\n"                                                    // 30
    "<Material id=\"2\">\n"                                            // 31
    "<AmbientReflectance>1 0 0</AmbientReflectance>\n"                 // 32
    "<DiffuseReflectance>1 0 0</DiffuseReflectance>\n"                 // 33
    "<SpecularReflectance>0 0 0</SpecularReflectance>\n"               // 34
    "<PhongExponent>1</PhongExponent>\n"                               // 35
    "</Material>\n"                                                    // 36
    "</Materials>\n"                                                   // 37
    "<VertexData>\n"                                                   // 38
    "-1 -1 -2\n"                                                       // 39
    "1 -1 -2\n"                                                        // 40
    "1 1 -2\n"                                                         // 41
    "-1 1 -2\n"                                                        // 42
    "</VertexData>\n"                                                  // 43
    "<Objects>\n"                                                      // 44
    "<Mesh id=\"1\">\n"                                                // 45
    "<Material>2</Material>\n"                                         // 46
    "<Faces>\n"                                                        // 47
    "1 2 3\n"                                                          // 48
    "</Faces>\n"                                                       // 49
    "</Mesh>\n"                                                        // 50
    "<Triangle id=\"1\">\n"                                            // 51
    "<Material>1</Material>\n"                                         // 52
    "<Indices>1 3 4</Indices>\n"                                       // 53
    "</Triangle>\n"                                                    // 54
    "</Objects>\n"                                                     // 55
    "</Scene>\n";                                                      // 56

// kBase in the CSE 461 format, as shared/tools/ceng477_to_cse461.py writes it.
const std::string kBaseConverted =
    "<scene><maxraytracedepth>2</maxraytracedepth><background>1 2 3</background>"
    "<shadowrayepsilon>1e-4</shadowrayepsilon><camera><position>0 0 0</position><gaze>0 0 -1</gaze><up>0 1 0</up>"
    "<nearplane>-1 1 -0.75 0.75</nearplane><neardistance>1</neardistance><imageresolution>32 24</imageresolution></camera>"
    "<lights><ambientlight>5 5 5</ambientlight><pointlight id=\"1\"><position>0 0 1</position>"
    "<intensity>100 100 100</intensity></pointlight></lights><materials>"
    "<material id=\"1\"><ambient>0.1 0.1 0.1</ambient><diffuse>0.5 0.5 0.5</diffuse><specular>0.2 0.2 0.2</specular>"
    "<phongexponent>10</phongexponent><mirrorreflectance>0.3 0.3 0.3</mirrorreflectance></material>"
    "<material id=\"2\"><ambient>1 0 0</ambient><diffuse>1 0 0</diffuse><specular>0 0 0</specular>"
    "<phongexponent>1</phongexponent><mirrorreflectance>0 0 0</mirrorreflectance></material></materials>"
    "<vertexdata>-1 -1 -2 1 -1 -2 1 1 -2 -1 1 -2</vertexdata><objects>"
    "<mesh id=\"1\"><materialid>2</materialid><faces>1 2 3</faces></mesh>"
    "<mesh id=\"2\"><materialid>1</materialid><faces>1 3 4</faces></mesh></objects></scene>\n";

std::string with(const std::string& from, const std::string& to, std::string text = kBase) {
  const std::size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << "test bug: '" << from << "' not in the scene";
  EXPECT_EQ(text.find(from, at + 1), std::string::npos) << "test bug: '" << from << "' is not unique";
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

// A directory of the test's own, for PLY files.
fs::path testDirectory() {
  const fs::path dir = testing::testOutputDirectory() / "ceng477_dialect";
  fs::create_directories(dir);
  return dir;
}

LoadOptions optionsWith(bool strict, int camera = 0, bool stream = true) {
  LoadOptions options;
  options.strict = strict;
  options.camera = camera;
  options.streamBlocks = stream;
  return options;
}

LoadedScene load(const std::string& xml, const LoadOptions& options = {}) {
  return loadSceneText(xml, "t.xml", testDirectory(), options);
}

std::string errorOf(const std::string& xml, const LoadOptions& options = {}) {
  try {
    load(xml, options);
  } catch (const SceneError& e) {
    return e.what();
  }
  ADD_FAILURE() << "the scene loaded";
  return "";
}

void expectError(const std::string& xml, int line, const std::string& part, const LoadOptions& options = {}) {
  const std::string message = errorOf(xml, options);
  EXPECT_EQ(message.rfind("t.xml:" + std::to_string(line) + ": error: ", 0), 0u) << message;
  EXPECT_NE(message.find(part), std::string::npos) << message;
}

::testing::AssertionResult hasWarning(const LoadedScene& loaded, int line, const std::string& part) {
  std::string all;
  for (const Diagnostic& d : loaded.warnings) {
    if (d.where.line == line && d.message.find(part) != std::string::npos) return ::testing::AssertionSuccess();
    all += "\n  " + d.format();
  }
  return ::testing::AssertionFailure() << "no warning at line " << line << " with '" << part << "'; have:" << all;
}

void expectSameScene(const Scene& a, const Scene& b) {
  EXPECT_TRUE(a.parameters() == b.parameters());
  testing::expectSameGeometry(a.geometry(), b.geometry());
  ASSERT_EQ(a.meshes.size(), b.meshes.size());
  for (std::size_t i = 0; i < a.meshes.size(); ++i) EXPECT_EQ(a.meshes[i].id, b.meshes[i].id);
}

// ---------------------------------------------------------------- mappings

TEST(Ceng477Dialect, ReadsAsItsConversionWithoutWarnings) {
  RAYVIEW_SKIP_WITHOUT_SHARED();
  const LoadedScene loaded = load(kBase, optionsWith(true));
  EXPECT_TRUE(loaded.warnings.empty());
  const Scene& s = loaded.scene;
  EXPECT_EQ(s.background, Color(1, 2, 3));
  EXPECT_EQ(s.shadowRayEpsilon, 1e-4);
  EXPECT_EQ(s.maxRayDepth, 2);
  EXPECT_EQ(s.camera.width, 32);
  ASSERT_EQ(s.materials.size(), 2u);
  EXPECT_EQ(s.materials[0].mirror, Color(0.3f));  // no type="mirror" anywhere: MirrorReflectance decides
  ASSERT_EQ(s.triangles.size(), 2u);
  EXPECT_EQ(s.materialOf(0), 1u);  // <Material>2</Material>: the second material
  EXPECT_EQ(s.materialOf(1), 0u);  // the <Triangle> is a one-face mesh after it
  expectSameScene(s, load(kBaseConverted).scene);
}

TEST(Ceng477Dialect, TakesTheCourseDefaults) {
  std::string xml = with("<BackgroundColor>1 2 3</BackgroundColor>", "");
  xml = with("<ShadowRayEpsilon>1e-4</ShadowRayEpsilon>", "", xml);
  xml = with("<MaxRecursionDepth>2</MaxRecursionDepth>", "", xml);
  xml = with("<AmbientLight>5 5 5</AmbientLight>", "", xml);
  xml = with("<MirrorReflectance>0.3 0.3 0.3</MirrorReflectance>", "", xml);
  const LoadedScene loaded = load(xml);
  EXPECT_EQ(loaded.scene.shadowRayEpsilon, 1e-3);  // the course parser's default, not rayview's robust offset
  EXPECT_EQ(loaded.scene.maxRayDepth, 0);
  EXPECT_EQ(loaded.scene.background, Color(0.0f));
  EXPECT_FALSE(loaded.scene.materials[0].isMirror());
  EXPECT_TRUE(hasWarning(loaded, 1, "no <MaxRecursionDepth>: using 0"));
  EXPECT_TRUE(hasWarning(loaded, 1, "no <BackgroundColor>: using black"));
  EXPECT_TRUE(hasWarning(loaded, 1, "no <AmbientLight>: using black"));
  EXPECT_EQ(loaded.warnings.size(), 3u);
}

TEST(Ceng477Dialect, ChecksIntersectionTestEpsilonAndShadowRayEpsilon) {
  const std::string eps = "<ShadowRayEpsilon>1e-4</ShadowRayEpsilon>";
  EXPECT_TRUE(load(with(eps, eps + "<IntersectionTestEpsilon>1e-6</IntersectionTestEpsilon>"), optionsWith(true)).warnings.empty());
  expectError(with(eps, eps + "<IntersectionTestEpsilon>-1</IntersectionTestEpsilon>"), 3, "must be >= 0");
  expectError(with(eps, "<ShadowRayEpsilon>-1</ShadowRayEpsilon>"), 3, "<ShadowRayEpsilon>: must be >= 0");
  expectError(with(eps, eps + eps), 3, "duplicate <ShadowRayEpsilon> inside <Scene>");
}

TEST(Ceng477Dialect, NamesMaterialsByPosition) {
  std::string xml = with("<Material id=\"1\">", "<Material id=\"7\">");
  xml = with("<Material id=\"2\">", "<Material id=\"3\">", xml);
  const LoadedScene loaded = load(xml);
  EXPECT_TRUE(hasWarning(loaded, 23, "material ids are not 1, 2, 3... in order"));
  EXPECT_EQ(loaded.scene.materials[0].id, "1");
  EXPECT_EQ(loaded.scene.materialOf(0), 1u);
  expectError(with("<Material>2</Material>", "<Material>3</Material>"), 46, "material \"3\" is not defined");
  expectError(with("<Material>2</Material>", "<Material>0</Material>"), 46, "expected a material number");
  expectError(with("<PhongExponent>1</PhongExponent>", ""), 31, "<Material id=\"2\"> has no <PhongExponent>");
}

TEST(Ceng477Dialect, ReflectsOnlyMarkedMirrorsWhenAFileMarksThem) {
  const std::string specular = "<SpecularReflectance>0 0 0</SpecularReflectance>";
  std::string xml = with(specular, specular + "<MirrorReflectance>1 1 1</MirrorReflectance>");
  EXPECT_TRUE(load(xml).scene.materials[1].isMirror());  // before 2021: MirrorReflectance decides
  xml = with("<Material id=\"1\">", "<Material id=\"1\" type=\"mirror\">", xml);
  const LoadedScene loaded = load(xml);
  EXPECT_TRUE(loaded.scene.materials[0].isMirror());
  EXPECT_FALSE(loaded.scene.materials[1].isMirror());
  EXPECT_TRUE(hasWarning(loaded, 31, "has a <MirrorReflectance> but no type=\"mirror\": not a mirror"));
  EXPECT_TRUE(hasWarning(load(with("<Material id=\"2\">", "<Material id=\"2\" type=\"dielectric\">")), 31,
                         "type=\"dielectric\" is not a material rayview renders"));
}

const std::string kSecondCamera =
    "</Camera><Camera id=\"2\"><Position>0 0 5</Position><Gaze>0 0 -1</Gaze><Up>0 1 0</Up>"
    "<NearPlane>-2 2 -1 1</NearPlane><NearDistance>2</NearDistance><ImageResolution>16 8</ImageResolution>"
    "<ImageName>two.ppm</ImageName></Camera>\n</Cameras>";

TEST(Ceng477Dialect, ReadsTheCameraAskedFor) {
  const std::string xml = with("</Camera>\n</Cameras>", kSecondCamera);
  const LoadedScene first = load(xml);
  EXPECT_EQ(first.scene.camera.width, 32);
  EXPECT_TRUE(hasWarning(first, 6, "<Cameras> has 2 cameras: rendering the first (choose another with --camera N)"));
  const LoadedScene second = load(xml, optionsWith(true, 2));
  EXPECT_TRUE(second.warnings.empty());
  EXPECT_EQ(second.scene.camera.position, glm::dvec3(0, 0, 5));
  EXPECT_EQ(second.scene.camera.width, 16);
  EXPECT_EQ(second.scene.camera.left, -2.0);
  expectError(xml, 5, "camera 3 was asked for, but <Cameras> has 2 cameras", optionsWith(false, 3));
  expectError(kBaseConverted, 1, "camera 2 was asked for, but the file has one <camera>", optionsWith(false, 2));
}

TEST(Ceng477Dialect, RefusesOrWarnsAboutCamerasItCannotHonour) {
  expectError(with("<Camera id=\"1\">", "<Camera id=\"1\" type=\"lookAt\">"), 6, "camera type \"lookAt\" is not supported");
  expectError(with("<Gaze>0 0 -1</Gaze>", ""), 6, "<Camera> has no <Gaze>");
  const LoadedScene loaded = load(with("<ImageName>out.ppm</ImageName>", "<NumSamples>4</NumSamples>"));
  EXPECT_TRUE(hasWarning(loaded, 13, "<NumSamples>4</NumSamples>: rendered with one sample per pixel"));
  EXPECT_TRUE(load(with("<ImageName>out.ppm</ImageName>", "<NumSamples>1</NumSamples>"), optionsWith(true)).warnings.empty());
}

TEST(Ceng477Dialect, DropsObjectsAndLightsItCannotRenderWithALocatedWarning) {
  const std::string sphere = "</Triangle>\n<Sphere id=\"1\"><Material>1</Material><Center>1</Center><Radius>0.5</Radius></Sphere>";
  const std::string xml = with("</Triangle>\n", sphere + "\n");
  const LoadedScene loaded = load(xml);
  EXPECT_EQ(loaded.scene.triangles.size(), 2u);
  EXPECT_TRUE(hasWarning(loaded, 55, "<Sphere> is a CENG477 object rayview does not render (triangle meshes only): dropped"));
  expectError(xml, 55, "<Sphere> is a CENG477 object rayview does not render", optionsWith(true));

  const LoadedScene light = load(with("</PointLight>", "</PointLight><SpotLight id=\"1\"></SpotLight>"));
  EXPECT_TRUE(hasWarning(light, 21, "<SpotLight> is a CENG477 light rayview does not render"));

  const LoadedScene moved = load(with("<Material>2</Material>", "<Material>2</Material><Transformations>t1</Transformations>"));
  EXPECT_TRUE(hasWarning(moved, 46, "<Mesh id=\"1\"> has <Transformations>, which rayview does not read: the object is dropped"));
  EXPECT_EQ(moved.scene.triangles.size(), 1u);
}

TEST(Ceng477Dialect, RefusesASceneOfSpheresOnly) {
  const std::size_t from = kBase.find("<Mesh id=\"1\">"), to = kBase.find("</Objects>");
  std::string xml = kBase;
  xml.replace(from, to - from, "<Sphere id=\"4\"><Material>1</Material><Center>1</Center><Radius>1</Radius></Sphere>\n");
  expectError(xml, 45, "no object of the scene can be rendered: rayview renders triangle meshes only, and the objects "
                       "here are not (the first is <Sphere id=\"4\">)");
}

TEST(Ceng477Dialect, ReadsAnElementsFirstTextOnlyAsTheCourseParserDoes) {
  const LoadedScene loaded = load(with("1 2 3\n</Faces>", "1 2 3 <!-- later faces are not read --> 1 3 4\n</Faces>"));
  EXPECT_EQ(loaded.scene.triangles.size(), 2u);  // the mesh's first face and the <Triangle>
  EXPECT_TRUE(hasWarning(loaded, 48, "<Faces>: text after a comment is ignored"));
  expectError(with("<Material>2</Material>", "<Material><!-- red -->2</Material>"), 46, "the value comes after a comment");
}

TEST(Ceng477Dialect, ReadsIndicesAsOneBasedOnly) {
  expectError(with("1 2 3\n</Faces>", "0 1 2\n</Faces>"), 48, "<Mesh id=\"1\">: vertex index 0 is out of range (the file has 4 vertices, indices 1..4)");
  expectError(with("<Indices>1 3 4</Indices>", "<Indices>1 3 5</Indices>"), 53, "<Triangle id=\"1\">: vertex index 5 is out of range");
  expectError(with("<Indices>1 3 4</Indices>", "<Indices>1 3</Indices>"), 53, "expected 3 vertex indices, found 2 numbers");
  expectError(with("<VertexData>", "<VertexData binaryFile=\"v.bin\">"), 38, "binary vertex files are not supported");
}

TEST(Ceng477Dialect, SavesAsTheHandoutFormatAndReadsBackTheSame) {
  // The viewer's Save writes what it loaded in the handout's format, a CENG477 scene too.
  const Scene loaded = load(kBase).scene;
  const Scene again = load(sceneToXml(loaded, "")).scene;
  expectSameScene(again, loaded);
}

// ---------------------------------------------------------------- PLY faces

void writeFile(const fs::path& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary);
  out << bytes;
}

// The base quad's two faces in a PLY file of its own vertices (little-endian binary), the second face a quad's fan.
std::string quadPly() {
  std::string ply = "ply\nformat binary_little_endian 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
                    "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";
  const float v[12] = {-1, -1, -2, 1, -1, -2, 1, 1, -2, -1, 1, -2};
  ply.append(reinterpret_cast<const char*>(v), sizeof v);
  const unsigned char n = 4;
  const std::int32_t f[4] = {0, 1, 2, 3};
  ply.append(reinterpret_cast<const char*>(&n), 1);
  ply.append(reinterpret_cast<const char*>(f), sizeof f);
  return ply;
}

Image renderOf(const Scene& scene) {
  auto geometry = prepareGeometry(scene, AccelKind::Embree, BvhBuild::Interactive);
  const Tracer tracer(scene, *geometry->accel, geometry->shading, RenderSettings{});
  ThreadPool pool(1);
  Image image;
  FrameStats stats;
  EXPECT_TRUE(renderFrame(tracer, scene.camera.width, scene.camera.height, pool, image, stats));
  return image;
}

TEST(Ceng477Dialect, ReadsFacesFromAPlyFileBesideTheScene) {
  writeFile(testDirectory() / "quad.ply", quadPly());
  // One mesh from the PLY (material 2) instead of the face and the triangle written out.
  const std::size_t from = kBase.find("<Mesh id=\"1\">"), to = kBase.find("</Objects>");
  std::string xml = kBase;
  xml.replace(from, to - from, "<Mesh id=\"1\"><Material>2</Material><Faces plyFile=\"quad.ply\"/></Mesh>\n");
  const LoadedScene loaded = load(xml, optionsWith(true));
  EXPECT_TRUE(loaded.warnings.empty());
  const Scene& s = loaded.scene;
  ASSERT_EQ(s.vertices.size(), 8u);  // <VertexData>'s, then the PLY's
  ASSERT_EQ(s.triangles.size(), 2u);
  EXPECT_EQ(s.triangles[0].vertex[0], 4u);
  EXPECT_EQ(s.triangles[1].vertex[2], 7u);
  // The same quad written out renders the same image, pixel for pixel.
  std::string written = with("<Material>1</Material>\n<Indices>1 3 4</Indices>", "<Material>2</Material>\n<Indices>1 3 4</Indices>");
  const Image fromPly = renderOf(s);
  const Image fromText = renderOf(load(written).scene);
  ASSERT_EQ(fromPly.width, 32);
  EXPECT_EQ(fromPly.rgb, fromText.rgb);
  EXPECT_NE(std::count(fromPly.rgb.begin(), fromPly.rgb.end(), 0), static_cast<std::ptrdiff_t>(fromPly.rgb.size()));
}

TEST(Ceng477Dialect, RefusesABadPlyFileNamingIt) {
  const std::string truncated = quadPly().substr(0, quadPly().size() - 3);
  writeFile(testDirectory() / "truncated.ply", truncated);
  const std::string faces = "<Faces>\n1 2 3\n</Faces>";
  const std::string message = errorOf(with(faces, "<Faces plyFile=\"truncated.ply\">\n\n</Faces>"));
  EXPECT_EQ(message.rfind("t.xml:47: error: <Faces plyFile=\"truncated.ply\">: the PLY file ", 0), 0u) << message;
  EXPECT_NE(message.find("truncated.ply: byte 49: face 0 of 1 declares a list of 4 values, more than the rest of the file holds"), std::string::npos) << message;
  expectError(with(faces, "<Faces plyFile=\"missing.ply\"/>"), 47, "missing.ply: not found");
  writeFile(testDirectory() / "not.ply", "solid x\n");
  expectError(with(faces, "<Faces plyFile=\"not.ply\"/>"), 47, "not.ply: is not a PLY file");
}

TEST(Ceng477Dialect, KeepsWrittenFacesToVertexData) {
  writeFile(testDirectory() / "quad.ply", quadPly());
  // Five indices the written faces may not reach, though the PLY's vertices follow <VertexData>'s.
  std::string xml = with("<Indices>1 3 4</Indices>", "<Indices>1 3 5</Indices>");
  xml = with("</Triangle>\n", "</Triangle>\n<Mesh id=\"2\"><Material>1</Material><Faces plyFile=\"quad.ply\"/></Mesh>\n", xml);
  expectError(xml, 53, "<Triangle id=\"1\">: vertex index 5 is out of range (the file has 4 vertices, indices 1..4)");
}

// ---------------------------------------------------------------- the course's files

struct CourseScene {
  std::string name;
  int camera;
};

std::vector<CourseScene> manifestScenes() {
  std::vector<CourseScene> scenes;
  std::ifstream manifest(testing::sharedDirectory() / "conformance" / "ceng477" / "manifest.tsv");
  std::string line;
  std::getline(manifest, line);  // header: scene, vintage, camera, ...
  while (std::getline(manifest, line)) {
    std::istringstream fields(line);
    std::string name, vintage, camera;
    std::getline(fields, name, '\t');
    std::getline(fields, vintage, '\t');
    std::getline(fields, camera, '\t');
    if (!name.empty()) scenes.push_back({name, std::stoi(camera)});
  }
  return scenes;
}

TEST(Ceng477Dialect, CourseFilesLoadAsTheirConversionsBothWays) {
  RAYVIEW_SKIP_WITHOUT_SHARED();
  const fs::path dir = testing::sharedDirectory() / "conformance" / "ceng477";
  const std::vector<CourseScene> scenes = manifestScenes();
  ASSERT_EQ(scenes.size(), 16u);
  for (const CourseScene& c : scenes) {
    SCOPED_TRACE(c.name);
    const LoadedScene converted = loadSceneFile(dir / (c.name + ".xml"));
    const fs::path original = dir / (c.name + ".ceng477.xml");
    const LoadedScene streamed = loadSceneFile(original, optionsWith(false, c.camera, true));
    expectSameScene(streamed.scene, converted.scene);
    // The DOM reading gives the same scene and warnings (what the fuzz target "scene" checks on any text).
    const LoadedScene dom = loadSceneFile(original, optionsWith(false, c.camera, false));
    expectSameScene(dom.scene, streamed.scene);
    ASSERT_EQ(dom.warnings.size(), streamed.warnings.size());
    for (std::size_t i = 0; i < dom.warnings.size(); ++i) EXPECT_EQ(dom.warnings[i].format(), streamed.warnings[i].format());
  }
}

}  // namespace
}  // namespace rayview
