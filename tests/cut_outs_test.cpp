// Cut-outs (a material's <alphaimage> and <alphacutoff>): a quad whose image is clear on its left half and opaque on
// its right, in front of a wall, lit by a point light between it and the camera. Every back-end, packets and single
// rays alike, shows the wall through the clear half, lets light through it, and keeps the opaque half's shadow.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "accel_backends.h"
#include "rayview/build_features.h"
#include "rayview/cut_outs.h"
#include "rayview/image.h"
#include "rayview/scene_loader.h"
#include "rayview/scene_writer.h"
#include "rayview/texture_image.h"
#include "rayview/tracer.h"
#include "support/rgba_png.h"
#include "support/scene_compare.h"
#include "support/test_directory.h"

namespace rayview {
namespace {

namespace fs = std::filesystem;

// Camera at the origin looking down -z, 8 x 2 pixels; the wall (material 1, no texture coordinates) at z = -4, the
// quad (material 2, x and y in -1..1, u = 0 at its left edge) at z = -2, the light at z = -1. Column by column the
// camera sees: wall lit, wall lit through the clear half (its shadow ray crosses it), wall through the clear half
// twice, the quad's opaque half twice, the wall in the opaque half's shadow, the wall lit.
std::string quadSceneXml(const std::string& cutOut) {
  return R"(<scene>
  <maxraytracedepth>0</maxraytracedepth>
  <background>0 0 0</background>
  <camera><position>0 0 0</position><gaze>0 0 -1</gaze><up>0 1 0</up>
    <nearplane>-1 1 -0.25 0.25</nearplane><neardistance>1</neardistance><imageresolution>8 2</imageresolution></camera>
  <lights><ambientlight>100 100 100</ambientlight>
    <pointlight id="1"><position>0 0 -1</position><intensity>1000 1000 1000</intensity></pointlight></lights>
  <materials>
    <material id="1"><ambient>0.2 0 0</ambient><diffuse>1 0 0</diffuse><specular>0 0 0</specular>
      <phongexponent>1</phongexponent><mirrorreflectance>0 0 0</mirrorreflectance></material>
    <material id="2"><ambient>0 0.2 0</ambient><diffuse>0 1 0</diffuse><specular>0 0 0</specular>
      <phongexponent>1</phongexponent><mirrorreflectance>0 0 0</mirrorreflectance>
      )" + cutOut + R"(</material>
  </materials>
  <vertexdata>-10 -10 -4 10 -10 -4 10 10 -4 -10 10 -4 -1 -1 -2 1 -1 -2 1 1 -2 -1 1 -2</vertexdata>
  <texturedata>0 0 1 0 1 1 0 1</texturedata>
  <objects>
    <mesh id="1"><materialid>1</materialid><faces>1 2 3 1 3 4</faces></mesh>
    <mesh id="2"><materialid>2</materialid><faces>5/1 6/2 7/3 5/1 7/3 8/4</faces></mesh>
  </objects>
</scene>
)";
}

class CutOutScene : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = testing::freshTestDirectory("rayview_cut_outs");
    std::ofstream(dir_ / "leaf.png", std::ios::binary)
        << testing::encodePngWithAlpha(4, 1, 4, testing::leftHalfClear(4, 1, 0, 255, 0));
  }
  void TearDown() override { fs::remove_all(dir_); }

  LoadedScene load(const std::string& xml, const std::string& name = "s.xml") {
    std::ofstream(dir_ / name) << xml;
    return loadSceneFile(dir_ / name);
  }
  fs::path dir_;
};

const std::string kCutOut = "<alphaimage>leaf.png</alphaimage><alphacutoff>0.5</alphacutoff>";

// Every pixel, one at a time (single rays) or all at once (packets of camera and shadow rays).
std::vector<Color> render(const Scene& scene, const Accel& accel, bool packets) {
  const ShadingGeometry shading = prepareShadingGeometry(scene, accel.origin());
  const Tracer tracer(scene, accel, shading, RenderSettings{});
  RayCounts counts;
  std::vector<PixelXY> pixels;
  for (int j = 0; j < scene.camera.height; ++j)
    for (int i = 0; i < scene.camera.width; ++i) pixels.push_back(PixelXY{i, j});
  std::vector<Color> out(pixels.size());
  if (packets) {
    for (std::size_t n = 0; n < pixels.size(); n += kRayPacket) {
      const int count = static_cast<int>(std::min<std::size_t>(kRayPacket, pixels.size() - n));
      tracer.tracePixels(&pixels[n], count, &out[n], counts);
    }
  } else {
    for (std::size_t n = 0; n < pixels.size(); ++n) out[n] = tracer.tracePixel(pixels[n].x, pixels[n].y, counts);
  }
  return out;
}

// The columns the scene's comment describes, in both rows.
void expectHoleAndShadow(const std::vector<Color>& image, const std::string& what) {
  const Color shadowedWall(20.0f, 0.0f, 0.0f);
  for (int j = 0; j < 2; ++j) {
    const Color* row = &image[static_cast<std::size_t>(j) * 8];
    for (int i : {0, 1, 2, 3, 7}) {
      EXPECT_GT(row[i].x, 30.0f) << what << ": the wall at column " << i << " is lit";
      EXPECT_EQ(row[i].y, 0.0f) << what << ": column " << i << " shows the wall, not the quad";
    }
    for (int i : {4, 5}) {
      EXPECT_EQ(row[i].x, 0.0f) << what << ": column " << i << " shows the quad";
      EXPECT_GT(row[i].y, 30.0f) << what << ": column " << i << " shows the lit quad";
    }
    EXPECT_EQ(row[6], shadowedWall) << what << ": the opaque half's shadow";
  }
}

struct Backend {
  std::string name;
  std::unique_ptr<Accel> accel;
};

std::vector<Backend> everyBackend(const Scene& scene, const CutOuts* cutOuts) {
  const glm::dvec3 origin = scene.camera.position;
  std::vector<Backend> backends;
  backends.push_back({"reference", makeReferenceAccel(scene, origin, nullptr, nullptr, cutOuts)});
  backends.push_back({"packet BVH", makePacketBvhAccel(scene, origin, 1, 1, cutOuts)});
  backends.push_back({"lean packet BVH", makePacketBvhAccel(scene, origin, 1, 4, cutOuts)});
#ifdef RAYVIEW_HAVE_EMBREE
  if (availableAccel(AccelKind::Embree) == AccelKind::Embree) {
    backends.push_back({"Embree", makeEmbreeAccel(scene, origin, EmbreeLayout::Fast, nullptr, nullptr, cutOuts)});
    backends.push_back(
        {"Embree compact", makeEmbreeAccel(scene, origin, EmbreeLayout::Compact, nullptr, nullptr, cutOuts)});
    if (__builtin_cpu_supports("avx2"))
      backends.push_back({"Embree AVX2", makeEmbreeAccelForIsa(scene, origin, "avx2", cutOuts)});
    backends.push_back({"Embree SSE4.2", makeEmbreeAccelForIsa(scene, origin, "sse4.2", cutOuts)});
  }
#endif
  return backends;
}

TEST_F(CutOutScene, EveryBackEndSeesAndLightsThroughTheClearHalf) {
  const LoadedScene loaded = load(quadSceneXml(kCutOut));
  EXPECT_TRUE(loaded.warnings.empty()) << loaded.warnings.front().format();
  const Scene& scene = loaded.scene;
  const std::unique_ptr<const CutOuts> cutOuts = CutOuts::of(scene, scene);
  ASSERT_TRUE(cutOuts);
  const std::vector<Backend> backends = everyBackend(scene, cutOuts.get());
  const std::vector<Color> reference = render(scene, *backends[0].accel, false);
  expectHoleAndShadow(reference, "reference");
  for (const Backend& b : backends) {
    ASSERT_TRUE(b.accel) << b.name;
    EXPECT_EQ(render(scene, *b.accel, false), reference) << b.name << ", single rays";
    EXPECT_EQ(render(scene, *b.accel, true), reference) << b.name << ", packets";
  }
}

// Packets of rays through the quad at every height and across both halves: each answer is the ray's own.
TEST_F(CutOutScene, PacketsAnswerAsSingleRays) {
  const Scene scene = load(quadSceneXml(kCutOut)).scene;
  const std::unique_ptr<const CutOuts> cutOuts = CutOuts::of(scene, scene);
  std::vector<Ray> rays;
  for (int k = 0; k < 4 * kRayPacket; ++k) {
    const double x = -1.2 + 2.4 * (k % kRayPacket + 0.5) / kRayPacket, y = -0.9 + 0.6 * (k / kRayPacket);
    rays.push_back(Ray{glm::dvec3(0.0), glm::dvec3(x, y, -2.0), 0.0, 1.5, kNoTriangle});  // to z = -3: the quad only
  }
  for (const Backend& b : everyBackend(scene, cutOuts.get())) {
    int hits = 0;
    for (std::size_t first = 0; first < rays.size(); first += kRayPacket) {
      std::optional<Hit> hitsOf[kRayPacket];
      bool blocked[kRayPacket];
      b.accel->closestHits(&rays[first], kRayPacket, hitsOf);
      b.accel->occludedMany(&rays[first], kRayPacket, blocked);
      for (int k = 0; k < kRayPacket; ++k) {
        const Ray& ray = rays[first + static_cast<std::size_t>(k)];
        const std::optional<Hit> single = b.accel->closestHit(ray);
        ASSERT_EQ(hitsOf[k].has_value(), single.has_value()) << b.name << " ray " << first + k;
        if (single) {
          EXPECT_EQ(hitsOf[k]->triangle, single->triangle) << b.name;
        }
        EXPECT_EQ(blocked[k], b.accel->occluded(ray)) << b.name << " ray " << first + k;
        EXPECT_EQ(blocked[k], single.has_value()) << b.name << " ray " << first + k;
        // The clear half (x < 0 where the ray meets the quad) never answers.
        const double xAtQuad = ray.direction.x;
        if (std::abs(xAtQuad) < 1.0) {
          EXPECT_EQ(single.has_value(), xAtQuad > 0.0) << b.name << " ray " << first + k;
        }
        hits += single.has_value();
      }
    }
    EXPECT_GT(hits, 0) << b.name;
  }
}

// Coverage is the alpha channel when the image has one, else its grey level; the cutoff decides the boundary
// (coverage < cutoff * 255 is a hole), and a face without texture coordinates is never cut.
TEST_F(CutOutScene, GreyMapsAndTheCutoffDecideTheHole) {
  // A 4x1 grey PPM: 0, 100, 200, 255 left to right.
  std::ofstream(dir_ / "grey.ppm", std::ios::binary) << "P5\n4 1\n255\n" << '\0' << char(100) << char(200) << char(255);
  const Scene scene = load(quadSceneXml("<alphaimage>grey.ppm</alphaimage><alphacutoff>0.5</alphacutoff>")).scene;
  const std::unique_ptr<const CutOuts> cutOuts = CutOuts::of(scene, scene);
  ASSERT_TRUE(cutOuts);
  // Triangle 2 is the quad's first (5/1 6/2 7/3): b1 weights corner (1, -1), b2 corner (1, 1).
  EXPECT_TRUE(cutOuts->hides(2, 0.05, 0.05));    // u ~ 0.1: texel 0, coverage 0
  EXPECT_TRUE(cutOuts->hides(2, 0.2, 0.15));     // u ~ 0.35: texel 1, coverage 100 < 127.5
  EXPECT_FALSE(cutOuts->hides(2, 0.3, 0.3));     // u ~ 0.6: texel 2, coverage 200
  EXPECT_FALSE(cutOuts->hides(0, 0.05, 0.05));   // the wall: no texture coordinates
  Scene strict = scene;
  strict.materials[1].alphaCutoff = 0.9f;  // 229.5: texel 2 becomes a hole, texel 3 (255) stays
  const std::unique_ptr<const CutOuts> strictCuts = CutOuts::of(strict, strict);
  EXPECT_TRUE(strictCuts->hides(2, 0.3, 0.3));
  EXPECT_FALSE(strictCuts->hides(2, 0.45, 0.5));
  Scene none = scene;
  none.materials[1].alphaImage.clear();
  EXPECT_EQ(CutOuts::of(none, none), nullptr);  // no cut-outs: the back-ends get no checks at all
}

// An image whose alpha channel is 255 everywhere is opaque, however dark its colour: it is no grey map.
TEST_F(CutOutScene, AnImageWithAnOpaqueAlphaHidesNothing) {
  std::vector<std::uint8_t> dark;
  for (int i = 0; i < 4; ++i) dark.insert(dark.end(), {0, 0, 0, 255});
  std::ofstream(dir_ / "dark.png", std::ios::binary) << testing::encodePngWithAlpha(4, 1, 4, dark);
  const Scene scene = load(quadSceneXml("<alphaimage>dark.png</alphaimage><alphacutoff>0.5</alphacutoff>")).scene;
  ASSERT_TRUE(scene.textureNamed("dark.png"));
  EXPECT_TRUE(scene.textureNamed("dark.png")->opaqueAlpha);
  EXPECT_EQ(CutOuts::of(scene, scene), nullptr) << "black, but opaque: no hole anywhere";
  // Written back (as import and texture_beside write images), it keeps its alpha and so stays opaque.
  std::string reason;
  const std::optional<Texture> again = detail::decodeImage(encodeTexturePng(*scene.textureNamed("dark.png")), reason);
  ASSERT_TRUE(again) << reason;
  EXPECT_TRUE(again->opaqueAlpha);
}

TEST_F(CutOutScene, ACutoffOutsideZeroToOneIsRefusedAtItsLine) {
  try {
    load(quadSceneXml("<alphaimage>leaf.png</alphaimage><alphacutoff>1.5</alphacutoff>"));
    ADD_FAILURE() << "a cutoff of 1.5 loaded";
  } catch (const SceneError& e) {
    EXPECT_EQ(e.diagnostic().where.line, 13);
    EXPECT_NE(std::string(e.what()).find("<alphacutoff>: must be from 0 to 1, found 1.5"), std::string::npos)
        << e.what();
  }
}

// The writer (its image renamed for where the copy lives) and the codec carry both fields; the copy renders alike.
TEST_F(CutOutScene, TheWriterAndTheCodecKeepTheCutOut) {
  const Scene scene = load(quadSceneXml("<alphaimage>leaf.png</alphaimage><alphacutoff>0.25</alphacutoff>")).scene;
  fs::create_directories(dir_ / "elsewhere");
  writeSceneFile(dir_ / "elsewhere" / "copy.xml", scene);
  const LoadedScene again = loadSceneFile(dir_ / "elsewhere" / "copy.xml");
  EXPECT_TRUE(again.warnings.empty()) << again.warnings.front().format();
  EXPECT_EQ(again.scene.materials[1].alphaImage, "../leaf.png");
  EXPECT_EQ(again.scene.materials[1].alphaCutoff, 0.25f);
  const auto cutOuts = CutOuts::of(scene, scene), copied = CutOuts::of(again.scene, again.scene);
  const auto a = makeReferenceAccel(scene, scene.camera.position, nullptr, nullptr, cutOuts.get());
  const auto b = makeReferenceAccel(again.scene, again.scene.camera.position, nullptr, nullptr, copied.get());
  EXPECT_EQ(render(scene, *a, false), render(again.scene, *b, false));

  const Scene decoded = testing::throughTheCodec(scene);
  const SceneParameters& parameters = decoded.parameters();
  const SceneGeometry& geometry = decoded.geometry();
  EXPECT_TRUE(parameters == scene.parameters());
  EXPECT_EQ(parameters.materials[1].alphaImage, "leaf.png");
  EXPECT_EQ(parameters.materials[1].alphaCutoff, 0.25f);
  EXPECT_TRUE(geometry.materialTextures == scene.materialTextures);
  ASSERT_NE(geometry.textureNamed("leaf.png"), nullptr);
  EXPECT_EQ(geometry.textureNamed("leaf.png")->alpha.size(), 4u);
}

}  // namespace
}  // namespace rayview
