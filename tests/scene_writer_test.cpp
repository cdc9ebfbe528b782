// "Save scene as": a scene written by rayview reads back equal, field by field, and renders the same image.
#include "rayview/scene_writer.h"

#include <cctype>
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include <algorithm>

#include "rayview/frame_renderer.h"
#include "rayview/prepared_scene.h"
#include "rayview/scene_loader.h"
#include "support/image_compare.h"
#include "support/scene_compare.h"

namespace rayview {
namespace {

namespace fs = std::filesystem;

// Real files: the course's scenes and peers' scenes of every yearly variant (2023, 2024 with its typos,
// 2025 with v/t/n faces and textures, 0-based faces).
std::vector<fs::path> roundTripScenes() {
  const fs::path shared = testing::sharedDirectory();
  std::vector<fs::path> scenes;
  for (const char* name : {"monkey", "bunny", "car", "low_poly", "scienceTree_1440x720", "bunny_2019"})
    scenes.push_back(shared / "conformance/ceng477" / (std::string(name) + ".xml"));
  for (const char* relative : {
           "handout/example_2024.xml",
           "handout/example_2024_skeleton_typos.xml",
           "peer-scenes/mertugr__mesh-trace/scenes/textured_cube.xml",
           "peer-scenes/mertugr__mesh-trace/scenes/textured_cube_png.xml",
           "peer-scenes/mertugr__mesh-trace/scenes/mirror_scene.xml",
           "peer-scenes/bashtag__Simple-Ray-Tracer/assets/scenes/scene_3_meshes_triangular_light_mirror.xml",
           "peer-scenes/borankurut__CSE-461/RayTracing/scene_chest.xml",
           "peer-scenes/akusgulu__raytracer/scenes/scene1.xml",
           "peer-scenes/aeakyuz__ray_tracer/scenes/sample.xml",
           "peer-scenes/Kurtburakk__Computer-Graphics-Cse-461/RayTracer/PA1/cghw1/examplexml/test3.xml",
           "peer-scenes/GtuOdevlerEmirhanAltunel__CSE461-HW1/assets/scene_cube.xml",
       })
    scenes.push_back(shared / relative);
  return scenes;
}

std::string nameOf(const fs::path& scene) { return scene.parent_path().filename().string() + "_" + scene.stem().string(); }

template <typename Vector>
void expectVecEq(const Vector& a, const Vector& b, const std::string& what) {
  for (int i = 0; i < Vector::length(); ++i) EXPECT_EQ(a[i], b[i]) << what << " [" << i << "]";
}

void expectSameScene(const Scene& a, const Scene& b) {
  EXPECT_EQ(a.maxRayDepth, b.maxRayDepth);
  expectVecEq(a.background, b.background, "background");
  EXPECT_EQ(a.shadowRayEpsilon, b.shadowRayEpsilon);

  const Camera &ca = a.camera, &cb = b.camera;
  expectVecEq(ca.position, cb.position, "camera position");
  expectVecEq(ca.gaze, cb.gaze, "camera gaze");
  expectVecEq(ca.up, cb.up, "camera up");
  EXPECT_EQ(ca.left, cb.left);
  EXPECT_EQ(ca.right, cb.right);
  EXPECT_EQ(ca.bottom, cb.bottom);
  EXPECT_EQ(ca.top, cb.top);
  EXPECT_EQ(ca.nearDistance, cb.nearDistance);
  EXPECT_EQ(ca.width, cb.width);
  EXPECT_EQ(ca.height, cb.height);

  expectVecEq(a.ambientLight, b.ambientLight, "ambient light");
  ASSERT_EQ(a.lights.of<PointLight>().size(), b.lights.of<PointLight>().size());
  for (std::size_t i = 0; i < a.lights.of<PointLight>().size(); ++i) {
    EXPECT_EQ(a.lights.of<PointLight>()[i].id, b.lights.of<PointLight>()[i].id);
    expectVecEq(a.lights.of<PointLight>()[i].position, b.lights.of<PointLight>()[i].position, "point light position");
    expectVecEq(a.lights.of<PointLight>()[i].intensity, b.lights.of<PointLight>()[i].intensity, "point light intensity");
  }
  ASSERT_EQ(a.lights.of<TriangularLight>().size(), b.lights.of<TriangularLight>().size());
  for (std::size_t i = 0; i < a.lights.of<TriangularLight>().size(); ++i) {
    const TriangularLight &la = a.lights.of<TriangularLight>()[i], &lb = b.lights.of<TriangularLight>()[i];
    EXPECT_EQ(la.id, lb.id);
    expectVecEq(la.vertex1, lb.vertex1, "triangular light vertex1");
    expectVecEq(la.vertex2, lb.vertex2, "triangular light vertex2");
    expectVecEq(la.vertex3, lb.vertex3, "triangular light vertex3");
    expectVecEq(la.intensity, lb.intensity, "triangular light intensity");
  }
  ASSERT_EQ(a.materials.size(), b.materials.size());
  for (std::size_t i = 0; i < a.materials.size(); ++i) {
    const Material &ma = a.materials[i], &mb = b.materials[i];
    EXPECT_EQ(ma.id, mb.id);
    expectVecEq(ma.ambient, mb.ambient, "ambient of " + ma.id);
    expectVecEq(ma.diffuse, mb.diffuse, "diffuse of " + ma.id);
    expectVecEq(ma.specular, mb.specular, "specular of " + ma.id);
    EXPECT_EQ(ma.phongExponent, mb.phongExponent);
    expectVecEq(ma.mirror, mb.mirror, "mirror of " + ma.id);
    EXPECT_EQ(ma.textureFactor, mb.textureFactor);
    EXPECT_EQ(ma.twoSided, mb.twoSided);
    EXPECT_EQ(ma.textureImage.empty(), mb.textureImage.empty());
    EXPECT_EQ(ma.alphaImage.empty(), mb.alphaImage.empty());
    if (!ma.alphaImage.empty()) {
      EXPECT_EQ(ma.alphaCutoff, mb.alphaCutoff);
    }
  }

  // The texture is found again from the new file's directory, with the same pixels.
  testing::expectSameGeometry(a, b);
}

bool mentionsTexture(const Diagnostic& d) { return d.message.find("texture") != std::string::npos; }
bool aboutRepeatedFaces(const Diagnostic& d) { return d.message.find("faces repeat the three vertices") != std::string::npos ||
                                                      d.message.find("face repeats the three vertices") != std::string::npos; }

class SceneWriterRoundTrip : public ::testing::TestWithParam<fs::path> {};

TEST_P(SceneWriterRoundTrip, ReadsBackEqualWithoutWarnings) {
  RAYVIEW_SKIP_WITHOUT_SHARED();
  const fs::path& source = GetParam();
  ASSERT_TRUE(fs::exists(source)) << source;
  const LoadedScene original = loadSceneFile(source);
  const fs::path written = testing::testOutputDirectory() / "scene_writer" / (nameOf(source) + ".xml");
  fs::create_directories(written.parent_path());
  writeSceneFile(written, original.scene);
  const LoadedScene again = loadSceneFile(written);
  expectSameScene(original.scene, again.scene);
  // Correct spellings, every element present: nothing to repair or default. Only a texture that the
  // original author never shipped may still be reported missing, and faces the original lists twice
  // (the scene's content, written as it is) are still reported.
  for (const Diagnostic& warning : again.warnings) {
    if (aboutRepeatedFaces(warning)) {
      EXPECT_TRUE(std::any_of(original.warnings.begin(), original.warnings.end(), aboutRepeatedFaces));
      continue;
    }
    EXPECT_TRUE(mentionsTexture(warning) && !original.scene.texture) << warning.format();
  }
  // Writing is deterministic: the same scene gives the same bytes.
  EXPECT_EQ(sceneToXml(again.scene, again.scene.textureImage), sceneToXml(again.scene, again.scene.textureImage));
}

INSTANTIATE_TEST_SUITE_P(RealScenes, SceneWriterRoundTrip, ::testing::ValuesIn(roundTripScenes()),
                         [](const ::testing::TestParamInfo<fs::path>& info) {
                           std::string name = nameOf(info.param);
                           for (char& c : name)
                             if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                           return name;
                         });

TEST(SceneWriter, WrittenSceneRendersTheSameImage) {
  RAYVIEW_SKIP_WITHOUT_SHARED();
  const fs::path source = testing::sharedDirectory() / "peer-scenes/mertugr__mesh-trace/scenes/textured_cube.xml";
  const LoadedScene original = loadSceneFile(source);
  const fs::path written = testing::testOutputDirectory() / "scene_writer" / "render_check.xml";
  fs::create_directories(written.parent_path());
  writeSceneFile(written, original.scene);
  const LoadedScene again = loadSceneFile(written);
  ASSERT_TRUE(again.scene.texture.has_value());

  ThreadPool pool(2);
  auto render = [&](const Scene& scene) {
    auto geometry = prepareGeometry(scene, AccelKind::Reference, BvhBuild::Interactive);
    const Tracer tracer(scene, *geometry->accel, geometry->shading, RenderSettings{});
    Image image;
    FrameStats stats;
    EXPECT_TRUE(renderFrame(tracer, scene.camera.width, scene.camera.height, pool, image, stats));
    return image;
  };
  const Image a = render(original.scene), b = render(again.scene);
  const testing::ImageDifference difference = testing::compareImages(b, a);
  EXPECT_EQ(difference.maxChannelDifference, 0) << difference.summary();
}

TEST(SceneWriter, UsesTheHandoutsSpellingsAndOneBasedFaces) {
  Scene scene;
  scene.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  scene.texCoords = {{0.5f, 0.25f}};
  scene.normals = {{0.0f, 0.0f, 1.0f}};
  scene.materials.push_back(Material{"a&b", {}, {}, {}, 2.0f, {0.1f, 0.2f, 0.3f}, 0.0f});
  scene.meshes.push_back(Mesh{"m", 0, 0, 2});
  Triangle plain;
  plain.vertex[0] = 0;
  plain.vertex[1] = 1;
  plain.vertex[2] = 2;
  FaceAttributes full;
  for (int k = 0; k < 3; ++k) {
    full.texCoord[k] = 0;
    full.normal[k] = 0;
  }
  full.texCoord[2] = kNoIndex;  // a normal without texture coordinates: v//n
  scene.addFace(plain);
  scene.addFace(plain, full);
  scene.lights.of<TriangularLight>().push_back(TriangularLight{"t", {0, 0, 0}, {1, 0, 0}, {0, 0, 1}, {1.0f, 2.0f, 3.0f}});
  const std::string xml = sceneToXml(scene, "tex.png");
  for (const char* expected : {"<background>", "<nearplane>", "<triangularlight id=\"t\">", "<intensity>",
                               "<mirrorreflectance>0.1 0.2 0.3</mirrorreflectance>", "id=\"a&amp;b\"",
                               "1 2 3\n", "1/1/1 2/1/1 3//1\n", "<textureimage>tex.png</textureimage>"})
    EXPECT_NE(xml.find(expected), std::string::npos) << expected << "\n" << xml;
  for (const char* misspelled : {"intesity", "traingular", "reflactance", "backgroundColor", "nearPlane"})
    EXPECT_EQ(xml.find(misspelled), std::string::npos) << misspelled;
}

// The two-sided flag is rayview's extension: written only for a material that has it, read back the same.
TEST(SceneWriter, TwoSidedMaterialsRoundTrip) {
  Scene scene;
  scene.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  scene.camera.width = scene.camera.height = 4;
  scene.materials.push_back(Material{"one", {}, {}, {}, 2.0f, {}, 0.0f});
  scene.materials.push_back(scene.materials[0]);
  scene.materials[1].id = "two";
  scene.materials[1].twoSided = true;
  scene.meshes.push_back(Mesh{"m", 1, 0, 1});
  Triangle t;
  t.vertex[1] = 1;
  t.vertex[2] = 2;
  scene.addFace(t);
  const std::string xml = sceneToXml(scene, "");
  EXPECT_EQ(xml.find("<twosided>"), xml.rfind("<twosided>")) << xml;
  EXPECT_NE(xml.find("<twosided>1</twosided>"), std::string::npos) << xml;
  const LoadedScene again = loadSceneText(xml, "t.xml", std::filesystem::temp_directory_path());
  ASSERT_EQ(again.scene.materials.size(), 2u);
  EXPECT_FALSE(again.scene.materials[0].twoSided);
  EXPECT_TRUE(again.scene.materials[1].twoSided);
}

TEST(SceneWriter, NumbersAreShortAndExact) {
  EXPECT_EQ(formatNumber(0.8f), "0.8");
  EXPECT_EQ(formatNumber(0.1), "0.1");
  EXPECT_EQ(formatNumber(-2.0), "-2");
  EXPECT_EQ(formatNumber(1e-300), "1e-300");
  for (const double v : {0.1 + 0.2, 1.0 / 3.0, 2.7538795471191406, 1e6 + 1e-9, -0.0})
    EXPECT_EQ(std::stod(formatNumber(v)), v) << formatNumber(v);
  // Floats read back through a double, exactly as the loader narrows them.
  for (const float v : {0.8f, 1.0f / 3.0f, 16777217.0f, 3.4e38f, 1e-40f, 0.800000011920929f})
    EXPECT_EQ(static_cast<float>(std::stod(formatNumber(v))), v) << formatNumber(v);
}

}  // namespace
}  // namespace rayview
