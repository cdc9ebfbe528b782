// Opening models through the import worker: each test writes its own model, opens it as rayview does
// (rayview/model_client.h: a child process), renders it small, and checks the picture: the model in the middle of
// the frame, lit, filling 80-95 % of it; materials and the texture where they belong; bad files refused by name.

#include <gtest/gtest.h>
#include <sys/stat.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <random>
#include <sstream>
#include <string>
#include <tuple>

#include "rayview/image.h"
#include "rayview/model_client.h"
#include "rayview/prepared_scene.h"
#include "rayview/scene_loader.h"
#include "rayview/scene_writer.h"
#include "rayview/tracer.h"
#include "support/image_compare.h"
#include "support/rgba_png.h"

namespace rayview {
namespace {

namespace fs = std::filesystem;

fs::path modelDirectory() {
  const fs::path dir = testing::testOutputDirectory() / "import";
  fs::create_directories(dir);
  return dir;
}

fs::path writeFile(const std::string& name, const std::string& bytes) {
  const fs::path path = modelDirectory() / name;
  std::ofstream(path, std::ios::binary) << bytes;
  return path;
}

template <class T>
void put(std::string& out, T value) {
  out.append(reinterpret_cast<const char*>(&value), sizeof value);
}

ModelImportOptions small() {
  ModelImportOptions options;
  options.width = 160;
  options.height = 90;
  return options;
}

Image render(const Scene& scene) {
  auto geometry = prepareGeometry(scene, AccelKind::Embree, BvhBuild::Interactive);
  const Tracer tracer(scene, *geometry, RenderSettings{});
  Image image(scene.camera.width, scene.camera.height);
  RayCounts counts;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      const Color c = glm::clamp(tracer.tracePixel(x, y, counts), Color(0.0f), Color(255.0f));
      for (int k = 0; k < 3; ++k) image.pixel(x, y)[k] = static_cast<std::uint8_t>(std::lround(c[k]));
    }
  return image;
}

bool isBackground(const Image& image, int x, int y, const Color& background) {
  const std::uint8_t* p = image.pixel(x, y);
  return std::abs(p[0] - background.x) < 1.5f && std::abs(p[1] - background.y) < 1.5f &&
         std::abs(p[2] - background.z) < 1.5f;
}

// The model is seen: the centre pixel is not background, and the pixels that are not span 80-95 % of the frame in
// its tighter dimension (the made-up camera fits the bounding box to 88 %).
void expectFramed(const Scene& scene, const std::string& name) {
  const Image image = render(scene);
  writeImageFile(modelDirectory() / (name + ".png"), image);
  EXPECT_FALSE(isBackground(image, image.width / 2, image.height / 2, scene.background)) << name;
  // Lit, not ambient alone (ambient light 30 on a reflectance of at most 0.9 is at most 27).
  const std::uint8_t* centre = image.pixel(image.width / 2, image.height / 2);
  EXPECT_GT(std::max({centre[0], centre[1], centre[2]}), 60) << name;
  int x0 = image.width, x1 = -1, y0 = image.height, y1 = -1;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x)
      if (!isBackground(image, x, y, scene.background)) {
        x0 = std::min(x0, x), x1 = std::max(x1, x), y0 = std::min(y0, y), y1 = std::max(y1, y);
      }
  const double fill = std::max((x1 - x0 + 1.0) / image.width, (y1 - y0 + 1.0) / image.height);
  EXPECT_GE(fill, 0.80) << name;
  EXPECT_LE(fill, 0.95) << name;
}

// A closed box: its silhouette reaches its bounding box's projected corners, so its extent is the framing's.
const double kBox[8][3] = {{0, 0, 0}, {2, 0, 0}, {2, 1, 0}, {0, 1, 0}, {0, 0, 1.5}, {2, 0, 1.5}, {2, 1, 1.5}, {0, 1, 1.5}};
const int kBoxQuads[6][4] = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4}, {2, 3, 7, 6}, {1, 2, 6, 5}, {0, 4, 7, 3}};

std::string boxObjWithTwoMaterials() {
  std::ostringstream obj;
  obj << "mtllib box.mtl\n";
  for (const auto& v : kBox) obj << "v " << v[0] << " " << v[1] << " " << v[2] << "\n";
  for (int f = 0; f < 6; ++f) {
    if (f == 0) obj << "usemtl red\n";
    if (f == 3) obj << "usemtl blue\n";
    obj << "f";
    for (int k = 0; k < 4; ++k) obj << " " << kBoxQuads[f][k] + 1;
    obj << "\n";
  }
  return obj.str();
}

std::string boxPly(double scale = 1.0, double offset = 0.0) {
  std::string ply = "ply\nformat binary_little_endian 1.0\nelement vertex 8\nproperty float x\nproperty float y\n"
                    "property float z\nelement face 6\nproperty list uchar int vertex_indices\nend_header\n";
  for (const auto& v : kBox)
    for (double c : v) put(ply, static_cast<float>(c * scale + offset));
  for (const auto& q : kBoxQuads) {
    put(ply, static_cast<std::uint8_t>(4));
    for (int k : q) put(ply, static_cast<std::int32_t>(k));
  }
  return ply;
}

std::string boxStl() {
  std::string stl(80, ' ');
  put(stl, static_cast<std::uint32_t>(12));
  for (const auto& q : kBoxQuads)
    for (const std::array<int, 3>& tri : {std::array<int, 3>{q[0], q[1], q[2]}, std::array<int, 3>{q[0], q[2], q[3]}}) {
      for (int k = 0; k < 3; ++k) put(stl, 0.0f);
      for (int k = 0; k < 3; ++k)
        for (double c : kBox[tri[k]]) put(stl, static_cast<float>(c));
      put(stl, static_cast<std::uint16_t>(0));
    }
  return stl;
}

TEST(ImportModel, ObjWithTwoMaterialsIsFramedLitAndKeepsItsColours) {
  writeFile("box.mtl", "newmtl red\nKd 0.9 0.1 0.1\nKs 0.4 0.4 0.4\nNs 60\nnewmtl blue\nKd 0.1 0.1 0.9\n");
  const ImportedModel model = importModel(writeFile("box.obj", boxObjWithTwoMaterials()), small());
  const Scene& scene = model.loaded.scene;
  EXPECT_EQ(scene.triangles.size(), 12u);
  ASSERT_EQ(scene.materials.size(), 2u);
  EXPECT_EQ(scene.materials[0].id, "red");
  EXPECT_FLOAT_EQ(scene.materials[0].diffuse.x, 0.9f);
  EXPECT_FLOAT_EQ(scene.materials[0].phongExponent, 60.0f);
  EXPECT_FLOAT_EQ(scene.materials[1].diffuse.z, 0.9f);
  EXPECT_EQ(scene.lights.of<PointLight>().size(), 3u);
  EXPECT_NE(model.summary.find("12 triangles"), std::string::npos) << model.summary;
  EXPECT_NE(model.summary.find("made up: camera"), std::string::npos) << model.summary;
  expectFramed(scene, "box_obj");
  // Both materials are on screen: a reddish and a bluish pixel.
  const Image image = render(scene);
  bool red = false, blue = false;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      const std::uint8_t* p = image.pixel(x, y);
      red |= p[0] > p[2] + 40;
      blue |= p[2] > p[0] + 40;
    }
  EXPECT_TRUE(red && blue);
}

TEST(ImportModel, BinaryPlyAndStlAreFramedAndLit) {
  const Scene ply = loadModelScene(writeFile("box.ply", boxPly()), small()).scene;
  EXPECT_EQ(ply.triangles.size(), 12u);  // quads cut in two
  expectFramed(ply, "box_ply");
  const Scene stl = loadModelScene(writeFile("box.stl", boxStl()), small()).scene;
  EXPECT_EQ(stl.triangles.size(), 12u);
  EXPECT_TRUE(stl.materials.at(0).twoSided);
  expectFramed(stl, "box_stl");
}

// The box with every face wound inward, as many exported models are: seen from outside, its faces show their
// backs. Imported materials are two-sided, so it is framed and lit, not a black silhouette.
std::string inwardBoxObj() {
  std::ostringstream obj;
  for (const auto& v : kBox) obj << "v " << v[0] << " " << v[1] << " " << v[2] << "\n";
  for (const auto& q : kBoxQuads) obj << "f " << q[3] + 1 << " " << q[2] + 1 << " " << q[1] + 1 << " " << q[0] + 1 << "\n";
  return obj.str();
}

TEST(ImportModel, FacesWoundInwardAreLitFromOutside) {
  const Scene scene = loadModelScene(writeFile("inward.obj", inwardBoxObj()), small()).scene;
  ASSERT_FALSE(scene.materials.empty());
  for (const Material& m : scene.materials) EXPECT_TRUE(m.twoSided) << m.id;
  expectFramed(scene, "box_inward");
  Scene oneSided = scene;
  for (Material& m : oneSided.materials) m.twoSided = false;
  const Image image = render(oneSided);
  const std::uint8_t* centre = image.pixel(image.width / 2, image.height / 2);
  EXPECT_LT(std::max({centre[0], centre[1], centre[2]}), 40);  // the one-sided shading this replaces: ambient only
}

// A UV sphere: every normal direction, so whichever way the light kit's lights point, some face takes their sum.
std::string sphereObj(const std::string& material) {
  std::ostringstream obj;
  if (!material.empty()) obj << "mtllib sphere.mtl\nusemtl " << material << "\n";
  const int rings = 24, segments = 48;
  obj << "v 0 1 0\nv 0 -1 0\n";
  for (int r = 1; r < rings; ++r)
    for (int s = 0; s < segments; ++s) {
      const double theta = M_PI * r / rings, phi = 2.0 * M_PI * s / segments;
      obj << "v " << std::sin(theta) * std::cos(phi) << " " << std::cos(theta) << " " << std::sin(theta) * std::sin(phi) << "\n";
    }
  auto at = [&](int r, int s) { return 3 + (r - 1) * segments + (s % segments); };  // 1-based, rings 1 .. rings-1
  for (int s = 0; s < segments; ++s) {
    obj << "f 1 " << at(1, s + 1) << " " << at(1, s) << "\n";
    obj << "f 2 " << at(rings - 1, s) << " " << at(rings - 1, s + 1) << "\n";
    for (int r = 1; r + 1 < rings; ++r)
      obj << "f " << at(r, s) << " " << at(r, s + 1) << " " << at(r + 1, s + 1) << " " << at(r + 1, s) << "\n";
  }
  return obj.str();
}

struct Exposure {
  double clipped = 0.0;  // the share of the model's pixels that are pure white
  double mean = 0.0;     // their mean over the three channels, 0..255
};

Exposure exposureOf(const Scene& scene, const std::string& name) {
  const Image image = render(scene);
  writeImageFile(modelDirectory() / (name + ".png"), image);
  std::size_t model = 0, white = 0;
  double sum = 0.0;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      if (isBackground(image, x, y, scene.background)) continue;
      const std::uint8_t* p = image.pixel(x, y);
      ++model;
      white += p[0] == 255 && p[1] == 255 && p[2] == 255;
      sum += (p[0] + p[1] + p[2]) / 3.0;
    }
  if (model == 0) return {};
  return {static_cast<double>(white) / model, sum / model};
}

// The made-up lights keep a white model below clipping, as F3D's and Blender's defaults do, and not dark.
TEST(ImportModel, TheLightKitKeepsAWhiteModelBelowClippingAndVisible) {
  writeFile("sphere.mtl", "newmtl white\nKd 1 1 1\nKs 0 0 0\nnewmtl shiny\nKd 1 1 1\nKs 0.5 0.5 0.5\nNs 40\n");
  for (const std::string material : {"white", "shiny"}) {
    const Exposure e = exposureOf(loadModelScene(writeFile(material + ".obj", sphereObj(material)), small()).scene,
                                  "sphere_" + material);
    EXPECT_LE(e.clipped, 0.01) << material;
    EXPECT_GE(e.mean, 30.0) << material;
  }
  const Exposure stl = exposureOf(loadModelScene(writeFile("plain.obj", sphereObj("")), small()).scene, "sphere_plain");
  EXPECT_LE(stl.clipped, 0.01);
  EXPECT_GE(stl.mean, 30.0);
}

// A dark model (a dark texture's mean as its colour, a dark grey plastic) is lit brighter, as much as makes its
// brightest colour lit as white would be, so it is not left near black; a white one keeps the plain kit.
TEST(ImportModel, TheLightKitLightsADarkModelBrighter) {
  writeFile("sphere.mtl", "newmtl dark\nKd 0.08 0.08 0.08\nKs 0 0 0\nnewmtl white\nKd 1 1 1\nKs 0 0 0\n");
  const Scene dark = loadModelScene(writeFile("dark.obj", sphereObj("dark")), small()).scene;
  const Scene white = loadModelScene(writeFile("white.obj", sphereObj("white")), small()).scene;
  const Exposure e = exposureOf(dark, "sphere_dark");
  EXPECT_GE(e.mean, 30.0);
  EXPECT_EQ(e.clipped, 0.0);
  const float ratio = dark.lights.of<PointLight>()[0].intensity.x / white.lights.of<PointLight>()[0].intensity.x;
  EXPECT_EQ(ratio, 4.0f);  // at most four times: 1 / 0.08 would be 12.5
}

// Sizes where a fixed epsilon would fail (docs/numerics.md): the made-up scene scales with the model, so the
// picture is the same box, framed and lit.
TEST(ImportModel, TinyAndHugeModelsAreFramedAndLit) {
  expectFramed(loadModelScene(writeFile("tiny.ply", boxPly(1e-6)), small()).scene, "box_tiny");
  expectFramed(loadModelScene(writeFile("huge.ply", boxPly(1e6)), small()).scene, "box_huge");
  expectFramed(loadModelScene(writeFile("far.ply", boxPly(1e-2, 1e3)), small()).scene, "box_far");
}

TEST(ImportModel, UpZLooksAlongTheModelsZ) {
  ModelImportOptions options = small();
  options.up = ModelUpAxis::Z;
  const Scene scene = loadModelScene(writeFile("box_z.ply", boxPly()), options).scene;
  EXPECT_EQ(scene.camera.up, glm::dvec3(0, 0, 1));
  expectFramed(scene, "box_up_z");
}

// A quad whose base colour is `png` (the .glb's own image), its material `material` (JSON).
std::string quadGlb(const std::string& png, const std::string& material) {
  std::string bin;
  for (float v : {-1.f, -1.f, 0.f, 1.f, -1.f, 0.f, 1.f, 1.f, 0.f, -1.f, 1.f, 0.f}) put(bin, v);
  for (float v : {0.f, 1.f, 1.f, 1.f, 1.f, 0.f, 0.f, 0.f}) put(bin, v);
  for (std::uint32_t i : {0u, 1u, 2u, 0u, 2u, 3u}) put(bin, i);
  bin += png;
  while (bin.size() % 4) bin.push_back('\0');
  std::string json =
      R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],)"
      R"("meshes":[{"primitives":[{"attributes":{"POSITION":0,"TEXCOORD_0":1},"indices":2,"material":0}]}],)" +
      std::string(R"("materials":[)") + material + "]," +
      R"("textures":[{"source":0}],"images":[{"bufferView":3,"mimeType":"image/png"}],)"
      R"("accessors":[{"bufferView":0,"componentType":5126,"count":4,"type":"VEC3","min":[-1,-1,0],"max":[1,1,0]},)"
      R"({"bufferView":1,"componentType":5126,"count":4,"type":"VEC2"},{"bufferView":2,"componentType":5125,"count":6,"type":"SCALAR"}],)"
      R"("bufferViews":[{"buffer":0,"byteOffset":0,"byteLength":48},{"buffer":0,"byteOffset":48,"byteLength":32},)"
      R"({"buffer":0,"byteOffset":80,"byteLength":24},{"buffer":0,"byteOffset":104,"byteLength":)" +
      std::to_string(png.size()) + R"(}],"buffers":[{"byteLength":)" + std::to_string(bin.size()) + "}]}";
  while (json.size() % 4) json.push_back(' ');
  std::string glb = "glTF";
  put(glb, std::uint32_t{2});
  put(glb, static_cast<std::uint32_t>(12 + 8 + json.size() + 8 + bin.size()));
  put(glb, static_cast<std::uint32_t>(json.size()));
  put(glb, std::uint32_t{0x4E4F534A});
  glb += json;
  put(glb, static_cast<std::uint32_t>(bin.size()));
  put(glb, std::uint32_t{0x004E4942});
  glb += bin;
  return glb;
}

// A quad whose base colour is a 4x4 PNG, red on the left and blue on the right; with `metalRoughMap`, the same image
// is its metallic-roughness map under glTF's default factors (metallic 1, roughness 1).
std::string texturedGlb(bool metalRoughMap = false) {
  Image texture(4, 4);
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 4; ++x) {
      texture.pixel(x, y)[0] = x < 2 ? 230 : 0;
      texture.pixel(x, y)[2] = x < 2 ? 0 : 230;
    }
  return quadGlb(encodePng(texture),
                 metalRoughMap ? R"({"pbrMetallicRoughness":{"baseColorTexture":{"index":0},)"
                                 R"("metallicRoughnessTexture":{"index":0}}})"
                               : R"({"pbrMetallicRoughness":{"baseColorTexture":{"index":0},"metallicFactor":0.0,"roughnessFactor":1.0}})");
}

// The quad of texturedGlb, its image's red left half clear (alpha 0), under glTF's alpha mode `mode`.
std::string cutOutGlb(const std::string& mode) {
  std::vector<std::uint8_t> rgba;
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 4; ++x)
      rgba.insert(rgba.end(), {std::uint8_t(x < 2 ? 230 : 0), 0, std::uint8_t(x < 2 ? 0 : 230), std::uint8_t(x < 2 ? 0 : 255)});
  return quadGlb(testing::encodePngWithAlpha(4, 4, 4, rgba),
                 R"({"alphaMode":")" + mode + R"(","alphaCutoff":0.3,"pbrMetallicRoughness":{"baseColorTexture":{"index":0},)"
                 R"("metallicFactor":0.0,"roughnessFactor":1.0}})");
}

TEST(ImportModel, GlbWithAnEmbeddedPngTextureShowsIt) {
  const ImportedModel model = importModel(writeFile("quad.glb", texturedGlb()), small());
  const Scene& scene = model.loaded.scene;
  ASSERT_EQ(scene.materials.size(), 1u);
  const Texture* texture = scene.textureOf(scene.materials[0]);
  ASSERT_TRUE(texture) << model.summary;
  EXPECT_EQ(texture->width, 4);
  EXPECT_EQ(scene.materials[0].textureImage, "quad_texture.png");  // the name `import` saves it under
  EXPECT_GT(scene.materials[0].textureFactor, 0.0f);
  const Image image = render(scene);
  writeImageFile(modelDirectory() / "quad_glb.png", image);
  // Along the middle row: red where the quad's left half is, blue where its right half is.
  int firstRed = -1, lastBlue = -1;
  for (int x = 0; x < image.width; ++x) {
    const std::uint8_t* p = image.pixel(x, image.height / 2);
    if (p[0] > p[2] + 30 && firstRed < 0) firstRed = x;
    if (p[2] > p[0] + 30) lastBlue = x;
  }
  EXPECT_GE(firstRed, 0);
  EXPECT_GT(lastBlue, firstRed);
}

// glTF's alpha mode MASK: the base colour's alpha is the cut-out, at the file's cutoff; the clear red half is not
// drawn. BLEND is drawn the same way, at 0.5, and the summary says so.
TEST(ImportModel, AGltfMaskIsACutOut) {
  const ImportedModel model = importModel(writeFile("leaf.glb", cutOutGlb("MASK")), small());
  const Scene& scene = model.loaded.scene;
  ASSERT_EQ(scene.materials.size(), 1u);
  const Material& m = scene.materials[0];
  EXPECT_EQ(m.alphaImage, m.textureImage);
  EXPECT_EQ(m.alphaCutoff, 0.3f);
  ASSERT_NE(scene.textureNamed(m.alphaImage), nullptr);
  EXPECT_EQ(scene.textureNamed(m.alphaImage)->alpha.size(), 16u);
  const Image image = render(scene);
  int red = 0, blue = 0;
  for (int x = 0; x < image.width; ++x) {
    const std::uint8_t* p = image.pixel(x, image.height / 2);
    red += p[0] > p[2] + 30;
    blue += p[2] > p[0] + 30;
  }
  EXPECT_EQ(red, 0) << "the clear half is drawn";
  EXPECT_GT(blue, 0);
  EXPECT_EQ(model.summary.find("alpha blending"), std::string::npos) << model.summary;

  const ImportedModel blended = importModel(writeFile("glass.glb", cutOutGlb("BLEND")), small());
  EXPECT_EQ(blended.loaded.scene.materials[0].alphaCutoff, 0.5f);
  EXPECT_FALSE(blended.loaded.scene.materials[0].alphaImage.empty());
  EXPECT_NE(blended.summary.find("alpha blending (drawn as a cut-out at 0.5)"), std::string::npos) << blended.summary;
}

// The metallic-roughness map is kept per texel, and the terms the file shows readers of the handout's format are
// its average texel's: here green (roughness) is 0 everywhere and blue (metallic) 230 on half the texels, so
// metallic 0.45 and roughness 0, not the defaults' fully metallic, fully rough material whose diffuse colour is
// black and whose highlight covers everything. The base colour is the factor (white) times the texture's mean.
TEST(ImportModel, AMetallicRoughnessMapIsKeptAndScalesTheAverageTerms) {
  const Scene scene = loadModelScene(writeFile("metal.glb", texturedGlb(true)), small()).scene;
  ASSERT_EQ(scene.materials.size(), 1u);
  const Material& m = scene.materials[0];
  const float half = 115.0f / 255.0f;
  EXPECT_NEAR(m.baseColor.x, half, 1e-3f);
  EXPECT_EQ(m.baseColor.y, 0.0f);
  EXPECT_EQ(m.metallic, 1.0f);
  EXPECT_EQ(m.roughness, 1.0f);
  ASSERT_NE(scene.textureNamed(m.metalRoughImage), nullptr);
  EXPECT_EQ(scene.textureNamed(m.metalRoughImage)->width, 4);
  EXPECT_NEAR(m.specular.x, 0.04f + (half - 0.04f) * half, 1e-3f);
  EXPECT_GT(m.diffuse.x, 0.0f);
  EXPECT_EQ(m.phongExponent, 10000.0f);  // roughness 0: the sharpest lobe
  EXPECT_NEAR(m.mirror.x, half * half, 1e-3f);
}

TEST(ImportModel, ObjRoundTripGivesTheSameTrianglesBitForBitInFloat) {
  Scene scene;
  scene.camera.width = scene.camera.height = 8;
  scene.camera.nearDistance = 1.0;
  scene.materials.push_back(Material{"a", Color(0.1f), Color(0.5f), Color(0.2f), 10.0f});
  scene.materials.push_back(Material{"b", Color(0.1f), Color(0.2f, 0.7f, 0.1f), Color(0.0f), 1.0f});
  std::mt19937 random(7);
  std::uniform_real_distribution<double> coordinate(-1000.0, 1000.0);
  for (int i = 0; i < 300; ++i) scene.vertices.emplace_back(coordinate(random), coordinate(random) * 1e-4, coordinate(random));
  for (std::uint32_t i = 0; i + 2 < 300; i += 3) scene.addFace(Triangle{{i, i + 1, i + 2}});
  scene.meshes.push_back(Mesh{"first", 0, 0, 50});
  scene.meshes.push_back(Mesh{"second", 1, 50, 50});
  const fs::path xml = modelDirectory() / "roundtrip.xml", obj = modelDirectory() / "roundtrip.obj";
  writeSceneFile(xml, scene);
  exportOpenedScene(loadSceneFile(xml).scene, obj);
  const Scene back = loadModelScene(obj, small()).scene;
  ASSERT_EQ(back.triangles.size(), scene.triangles.size());
  for (std::size_t t = 0; t < scene.triangles.size(); ++t)
    for (int k = 0; k < 3; ++k) {
      const glm::dvec3& a = scene.vertices[scene.triangles[t].vertex[k]];
      const glm::dvec3& b = back.vertices[back.triangles[t].vertex[k]];
      for (int c = 0; c < 3; ++c) ASSERT_EQ(static_cast<float>(a[c]), static_cast<float>(b[c])) << t << " " << k;
    }
  EXPECT_EQ(back.materials.size(), 2u);
}

std::string errorOf(const fs::path& path) {
  try {
    loadModelScene(path, small());
  } catch (const SceneError& error) {
    EXPECT_EQ(error.diagnostic().where.file, path.string());
    return error.diagnostic().message;
  }
  ADD_FAILURE() << path << " loaded";
  return {};
}

TEST(ImportModel, BadFilesAreRefusedByName) {
  EXPECT_NE(errorOf(writeFile("empty.obj", "")).find("empty"), std::string::npos);
  EXPECT_NE(errorOf(writeFile("truncated.stl", boxStl().substr(0, 300))).find("truncated"), std::string::npos);
  std::string absurd = boxPly();
  absurd.replace(absurd.find("vertex 8"), 8, "vertex 4000000000");
  EXPECT_NE(errorOf(writeFile("absurd.ply", absurd)).find("more than the rest of the file"), std::string::npos);
  std::string nan = boxPly();
  const float quietNan = std::nanf("");
  std::memcpy(nan.data() + nan.find("end_header\n") + 11 + 4, &quietNan, 4);
  EXPECT_NE(errorOf(writeFile("nan.ply", nan)).find("not a finite number"), std::string::npos);
  std::string outOfRange = boxPly();
  const std::int32_t far = 99;
  std::memcpy(outOfRange.data() + outOfRange.size() - 4, &far, 4);
  EXPECT_NE(errorOf(writeFile("range.ply", outOfRange)).find("uses vertex 99"), std::string::npos);
  EXPECT_NE(errorOf(writeFile("inf.obj", "v 0 0 0\nv 1 0 0\nv inf 1 0\nf 1 2 3\n")).find("finite"), std::string::npos);
  EXPECT_NE(errorOf(writeFile("range.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n")), "");
  EXPECT_NE(errorOf(writeFile("garbage.gltf", "{ not json")), "");
}

// Assimp's known pitfalls, which rayview's own readers avoid.
TEST(ImportModel, PlyHeaderAfterABlankLineAndABigPlyReadWhole) {
  std::string newline(1, '\n');
  newline.append(boxPly());
  EXPECT_EQ(loadModelScene(writeFile("newline.ply", newline), small()).scene.triangles.size(), 12u);
  std::ostringstream big;
  big << "ply\nformat ascii 1.0\nelement vertex 3000\nproperty float x\nproperty float y\nproperty float z\n"
         "element face 2000\nproperty list uchar int vertex_indices\nend_header\n";
  for (int i = 0; i < 3000; ++i) big << i % 60 << " " << i / 60 << " " << i % 7 << "\n";
  for (int i = 0; i < 2000; ++i) big << "3 " << i << " " << i + 1 << " " << i + 60 << "\n";
  EXPECT_EQ(loadModelScene(writeFile("big.ply", big.str()), small()).scene.triangles.size(), 2000u);
}

// Normals and texture coordinates are kept as the 2025 format's, faces naming them.
TEST(ImportModel, NormalsAndTextureCoordinatesAreKept) {
  const Scene ply = loadModelScene(writeFile("normals.ply",
                                             "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                                             "property float z\nproperty float nx\nproperty float ny\nproperty float nz\n"
                                             "property float u\nproperty float v\n"
                                             "element face 1\nproperty list uchar int vertex_indices\nend_header\n"
                                             "0 0 0 0 0 2 0 0\n1 0 0 0 0 2 1 0\n0 1 0 0 0 2 0 0.5\n3 0 1 2\n"),
                                   small())
                       .scene;
  ASSERT_EQ(ply.normals.size(), 3u);
  EXPECT_EQ(ply.normals[0], glm::vec3(0, 0, 1));
  EXPECT_TRUE(ply.attributesOf(0).hasNormals());
  ASSERT_TRUE(ply.attributesOf(0).hasTexCoords());
  EXPECT_EQ(ply.texCoords[ply.attributesOf(0).texCoord[2]], glm::vec2(0, 0.5f));
  const Scene obj = loadModelScene(writeFile("uv.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nf 1/1 2/2 3/3\n"),
                                   small())
                       .scene;
  ASSERT_EQ(obj.texCoords.size(), 3u);
  EXPECT_TRUE(obj.attributesOf(0).hasTexCoords());
  EXPECT_EQ(obj.texCoords[obj.attributesOf(0).texCoord[1]], glm::vec2(1, 0));
}

// A glTF of one triangle at the origin facing +z, a camera at (0, 0, cameraZ) looking down -z and a point light of
// `intensity` at (0, 3, 3).
std::string triangleGltf(double cameraZ, double intensity) {
  std::string buffer;
  for (float v : {-1.f, -1.f, 0.f, 1.f, -1.f, 0.f, 0.f, 1.f, 0.f}) put(buffer, v);
  // The 36 bytes in base64, by hand: no encoder in the test.
  static const char kBase64[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string encoded;
  for (std::size_t i = 0; i < buffer.size(); i += 3) {
    const auto byte = [&](std::size_t k) { return static_cast<unsigned>(static_cast<unsigned char>(buffer[i + k])); };
    const unsigned triple = byte(0) << 16 | byte(1) << 8 | byte(2);
    for (int k = 3; k >= 0; --k) encoded.push_back(kBase64[(triple >> (6 * k)) & 63]);
  }
  return R"({"asset":{"version":"2.0"},"extensionsUsed":["KHR_lights_punctual"],)"
         R"("extensions":{"KHR_lights_punctual":{"lights":[{"type":"point","intensity":)" + std::to_string(intensity) +
         R"(,"color":[1,1,1]}]}},)"
         R"("scene":0,"scenes":[{"nodes":[0,1,2]}],"nodes":[{"mesh":0},{"camera":0,"translation":[0,0,)" +
         std::to_string(cameraZ) + R"(]},)"
         R"({"extensions":{"KHR_lights_punctual":{"light":0}},"translation":[0,3,3]}],)"
         R"("cameras":[{"type":"perspective","perspective":{"yfov":0.6,"znear":0.1,"aspectRatio":1.5}}],)"
         R"("meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}],)"
         R"("accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3","min":[-1,-1,0],"max":[1,1,0]}],)"
         R"("bufferViews":[{"buffer":0,"byteLength":36}],"buffers":[{"byteLength":36,)"
         R"("uri":"data:application/octet-stream;base64,)" + encoded + R"("}]})";
}

bool warned(const ImportedModel& model, const std::string& part) {
  for (const Diagnostic& w : model.loaded.warnings)
    if (w.message.find(part) != std::string::npos) return true;
  return false;
}

// A glTF's own camera and light are used when they show the model (a triangle seen from 5 units away, a light
// above it bright enough to see it by).
TEST(ImportModel, GltfsOwnCameraAndLightAreUsed) {
  const ImportedModel model = importModel(writeFile("camera.gltf", triangleGltf(5.0, 10.0)), small());
  const Scene& scene = model.loaded.scene;
  EXPECT_EQ(model.summary.find("camera"), std::string::npos) << model.summary;
  EXPECT_EQ(scene.camera.position, glm::dvec3(0, 0, 5));
  EXPECT_NEAR(scene.camera.top, std::tan(0.3), 1e-6);
  EXPECT_NEAR(scene.camera.right, std::tan(0.3) * 160.0 / 90.0, 1e-6);
  ASSERT_EQ(scene.lights.of<PointLight>().size(), 1u);
  EXPECT_EQ(scene.lights.of<PointLight>()[0].position, glm::dvec3(0, 3, 3));
  const Image image = render(scene);
  EXPECT_FALSE(isBackground(image, 80, 45, scene.background));
  EXPECT_TRUE(isBackground(image, 5, 5, scene.background));
  ModelImportOptions own = small();
  own.camera = own.lights = ModelViewSource::Rayview;  // --camera auto --lights kit
  const ImportedModel framed = importModel(writeFile("camera.gltf", triangleGltf(5.0, 10.0)), own);
  EXPECT_NE(framed.summary.find("made up: camera, key/fill/back lights"), std::string::npos) << framed.summary;
}

// Emission is kept (the surface shows its own light with no light on it), and so are vertex colours; neither is
// in the summary's "dropped".
TEST(ImportModel, EmissionAndVertexColoursAreKept) {
  std::string gltf = triangleGltf(5.0, 10.0);
  const std::string mesh = R"("attributes":{"POSITION":0})";
  gltf.replace(gltf.find(mesh), mesh.size(), mesh + R"(,"material":0)");
  gltf.insert(gltf.rfind('}'), R"(,"materials":[{"emissiveFactor":[1,0.5,0]}])");
  const ImportedModel model = importModel(writeFile("glow.gltf", gltf), small());
  EXPECT_NE(model.summary.find("dropped: nothing"), std::string::npos) << model.summary;
  Scene dark = model.loaded.scene;
  ASSERT_EQ(dark.materials.size(), 1u);
  EXPECT_EQ(dark.materials[0].emission, Color(255.0f, 127.5f, 0.0f));
  dark.lights = SceneLights{};
  dark.ambientLight = Color(0.0f);
  const Image image = render(dark);
  bool glows = false;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      const std::uint8_t* p = image.pixel(x, y);
      glows |= p[0] == 255 && p[1] == 128 && p[2] == 0;
    }
  EXPECT_TRUE(glows) << "no pixel shows the emission (255, 128, 0) in the dark";
  const ImportedModel colours = importModel(
      writeFile("colours.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                               "property float z\nproperty uchar red\nproperty uchar green\nproperty uchar blue\n"
                               "element face 1\nproperty list uchar int vertex_indices\nend_header\n"
                               "0 0 0 255 0 0\n1 0 0 0 255 0\n0 1 0 0 0 255\n3 0 1 2\n"),
      small());
  EXPECT_NE(colours.summary.find("dropped: nothing"), std::string::npos) << colours.summary;
  const std::vector<Color> expected = {Color(1, 0, 0), Color(0, 1, 0), Color(0, 0, 1)};
  EXPECT_EQ(colours.loaded.scene.vertexColors, expected);
  const ImportedModel plain = importModel(writeFile("plain.gltf", triangleGltf(5.0, 10.0)), small());
  EXPECT_NE(plain.summary.find("dropped: nothing"), std::string::npos) << plain.summary;
}

// An OBJ's `v x y z r g b` colours are kept by rayview's own OBJ reader: 0..1 as written, 0..255 as bytes, white
// for the vertices that have none, and not "dropped".
TEST(ImportModel, ObjVertexColoursAreKept) {
  const ImportedModel model = importModel(
      writeFile("colours.obj", "v 0 0 0 1 0 0\nv 1 0 0\nv 0 1 0 0 0.5 1\nf 1 2 3\n"), small());
  EXPECT_NE(model.summary.find("dropped: nothing"), std::string::npos) << model.summary;
  const std::vector<Color> expected = {Color(1, 0, 0), Color(1, 1, 1), Color(0, 0.5f, 1)};
  EXPECT_EQ(model.loaded.scene.vertexColors, expected);
  const ImportedModel bytes = importModel(writeFile("bytes.obj", "v 0 0 0 255 0 51\nv 1 0 0 0 255 0\nv 0 1 0 0 0 255\nf 1 2 3\n"), small());
  ASSERT_EQ(bytes.loaded.scene.vertexColors.size(), 3u);
  EXPECT_EQ(bytes.loaded.scene.vertexColors[0], Color(1.0f, 0.0f, 51.0f / 255.0f));
  const ImportedModel none = importModel(writeFile("none.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"), small());
  EXPECT_TRUE(none.loaded.scene.vertexColors.empty());
}

// A camera that looks away from the model, or a light too weak to see it by (1 cd at 4.2 units: 14 of 255), is
// replaced by rayview's with a warning; asked for, the file's is kept whatever it shows.
TEST(ImportModel, AFileCameraOrLightThatShowsNothingIsReplaced) {
  const fs::path away = writeFile("away.gltf", triangleGltf(-5.0, 10.0));
  const ImportedModel framed = importModel(away, small());
  EXPECT_NE(framed.summary.find("made up: camera"), std::string::npos) << framed.summary;
  EXPECT_TRUE(warned(framed, "the file's camera shows the model on 0 % of the frame"));
  expectFramed(framed.loaded.scene, "gltf_away");
  ModelImportOptions file = small();
  file.camera = file.lights = ModelViewSource::File;
  EXPECT_EQ(importModel(away, file).loaded.scene.camera.position, glm::dvec3(0, 0, -5));

  const fs::path dim = writeFile("dim.gltf", triangleGltf(5.0, 1.0));
  const ImportedModel lit = importModel(dim, small());
  EXPECT_NE(lit.summary.find("key/fill/back lights"), std::string::npos) << lit.summary;
  EXPECT_TRUE(warned(lit, "the file's lights give the model an irradiance of 14.2"));
  EXPECT_EQ(lit.loaded.scene.lights.of<PointLight>().size(), 3u);
  EXPECT_EQ(importModel(dim, file).loaded.scene.lights.of<PointLight>().size(), 1u);

  // 1000 cd at 4.2 units: 14 000 of 255, a white frame; scaled to 200 with its place kept.
  const fs::path glaring = writeFile("glaring.gltf", triangleGltf(5.0, 1000.0));
  const ImportedModel exposed = importModel(glaring, small());
  EXPECT_TRUE(warned(exposed, "which would turn it white"));
  ASSERT_EQ(exposed.loaded.scene.lights.of<PointLight>().size(), 1u);
  const PointLight& light = exposed.loaded.scene.lights.of<PointLight>()[0];
  EXPECT_EQ(light.position, glm::dvec3(0, 3, 3));
  EXPECT_NEAR(light.intensity.x / 18.0f, 200.0f, 0.01f);  // I / d^2 at the centre, d^2 = 3^2 + 3^2
  EXPECT_EQ(importModel(glaring, file).loaded.scene.lights.of<PointLight>()[0].intensity.x, 255000.0f);
}

// A worker that dies or answers garbage is a clean error about the file, never a crash of rayview.
TEST(ImportModel, AWorkerThatDiesIsACleanError) {
  const fs::path model = writeFile("fine.ply", boxPly());
  for (const auto& [name, script, expected] :
       {std::tuple{"crash.sh", "#!/bin/sh\nkill -SEGV $$\n", "crashed"},
        std::tuple{"garbage.sh", "#!/bin/sh\necho hello\n", "unusable"},
        std::tuple{"fails.sh", "#!/bin/sh\nexit 3\n", "exit status 3"}}) {
    const fs::path worker = writeFile(name, script);
    ::chmod(worker.c_str(), 0755);
    ::setenv("RAYVIEW_IMPORT_WORKER", worker.c_str(), 1);
    EXPECT_NE(errorOf(model).find(expected), std::string::npos) << name;
  }
  ::unsetenv("RAYVIEW_IMPORT_WORKER");
}

// A real crash of Assimp (its glTF binary reader on these bytes, found by fuzz_import): a clean error.
TEST(ImportModel, AnAssimpCrashIsACleanError) {
  std::ifstream in(testing::sourceDirectory() / "tests/fuzz_regressions/import/glb_assimp_segv_isolated_by_worker.bin",
                   std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  ASSERT_GT(bytes.size(), 1u);
  EXPECT_NE(errorOf(writeFile("assimp_crash.glb", bytes.substr(1))), "");  // "the importer crashed ..." with 5.2.5
}

TEST(ImportModel, ModelFilesByExtension) {
  EXPECT_TRUE(isModelFile("a.OBJ"));
  EXPECT_TRUE(isModelFile("dir/a.glb"));
  EXPECT_TRUE(isModelFile("a.ply"));
  EXPECT_FALSE(isModelFile("scene.xml"));
  EXPECT_FALSE(isModelFile("a.mesh.xml"));
  EXPECT_FALSE(isModelFile("a.png"));
  EXPECT_FALSE(isModelFile("obj"));
}

}  // namespace
}  // namespace rayview
