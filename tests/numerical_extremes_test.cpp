// The numerical extremes the renderer must survive, each printing the figure it reaches (SPEC section 6):
//   scale        conformance scenes scaled by 1e-6..1e6 (intensities by factor^2, no <shadowrayepsilon>)
//                render as at scale 1: >= 99.9 % of pixels within +-1;
//   translation  conformance scenes moved by 1e3, 1e5, 1e6 along each axis: >= 99.9 % within +-1;
//   acne         a tessellated plane lit from 30 down to 0.1 degrees above it, at scales 1e-4..1e4, shows
//                the lit value everywhere: no self-shadowed pixel;
//   degenerate   zero-area triangles, repeated and non-finite vertices, vertices at 1e30, Phong exponents
//                0 and 1e6, intensities 0 and 1e30, two facing mirrors at depth 1000: no NaN or Inf in the
//                unclamped radiance, an image, no crash; the mirrors' cost is linear in the depth.
// Conformance images are rendered at a quarter of their resolution (same frustum) to keep the tests fast.
// Pixels that see a face listed twice (coincident copies, opposite normals: dragon_lowres_2017 has 380)
// are left to rounding by the scene itself; they are counted, printed and left out of the comparison.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "rayview/frame_renderer.h"
#include "rayview/prepared_scene.h"
#include "rayview/scene_loader.h"
#include "support/coincident_faces.h"
#include "support/conformance_scenes.h"
#include "support/image_compare.h"
#include "support/numerics_scenes.h"
#include "support/scene_builder.h"
#include "support/scene_transforms.h"

namespace rayview {
namespace {

// Under a sanitizer a quarter of the pixels: it checks memory use, which the pixel count does not change, and the
// sweeps below render each scene 8 to 10 times.
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
constexpr int kResolutionDivisor = 8;
#else
constexpr int kResolutionDivisor = 4;
#endif
constexpr double kMinWithinOnePercent = 99.9;

AccelKind defaultAccel() { return availableAccel(AccelKind::Embree); }

std::string accelName(AccelKind kind) { return std::string(toString(kind)); }

// ---- Scale and translation ---------------------------------------------------------------------------

class ConformanceScene : public ::testing::TestWithParam<std::filesystem::path> {
 protected:
  Scene load() {
    Scene scene = loadSceneFile(GetParam()).scene;
    testing::reduceResolution(scene, kResolutionDivisor);
    coincident_ = testing::coincidentFacePixels(scene);
    const auto left = std::count(coincident_.begin(), coincident_.end(), true);
    if (left > 0)
      std::printf("[ figures  ] %s: %zu duplicated faces; %ld pixels see one and are left out\n",
                  GetParam().stem().string().c_str(), testing::countDuplicatedFaces(scene), static_cast<long>(left));
    const std::vector<bool> onEdges = testing::boundaryEdgePixels(scene);
    const auto edgePixels = std::count(onEdges.begin(), onEdges.end(), true);
    if (edgePixels > 0)
      std::printf("[ figures  ] %s: %ld pixels' rays pass exactly through a boundary edge and are left out\n",
                  GetParam().stem().string().c_str(), static_cast<long>(edgePixels));
    for (std::size_t p = 0; p < onEdges.size(); ++p) coincident_[p] = coincident_[p] || onEdges[p];
    return scene;
  }
  // Compares with `expected`, prints the figure, writes difference images when below the threshold.
  void expectSame(Image actual, const Image& expected, const std::string& what) const {
    testing::copyMaskedPixels(actual, expected, coincident_);
    const testing::ImageDifference d = testing::compareImages(actual, expected);
    std::printf("[ figures  ] %s %s: %s\n", GetParam().stem().string().c_str(), what.c_str(), d.summary().c_str());
    EXPECT_GE(d.withinOnePercent, kMinWithinOnePercent) << what << ": " << d.summary();
    if (d.withinOnePercent < kMinWithinOnePercent)
      testing::writeDifferenceImages("extremes-" + GetParam().stem().string() + "-" + what, actual, expected);
  }

  std::vector<bool> coincident_;
};

class ScaleInvariance : public ConformanceScene {};
class TranslationInvariance : public ConformanceScene {};

TEST_P(ScaleInvariance, SameImageFrom1eMinus6To1e6) {
  Scene base = load();
  base.shadowRayEpsilon.reset();  // the condition under test: the robust offset, not a fixed length
  const Image expected = testing::renderChecked(base, defaultAccel()).image;
  for (double factor : {1e-6, 1e-3, 1e3, 1e6}) {
    Scene scaled = base;
    testing::scaleScene(scaled, factor);
    const testing::CheckedRender r = testing::renderChecked(scaled, defaultAccel());
    char what[32];
    std::snprintf(what, sizeof what, "scale %g", factor);
    expectSame(r.image, expected, what);
    EXPECT_EQ(r.nonFinitePixels, 0);
  }
}

TEST_P(TranslationInvariance, SameImageMovedBy1e3To1e6) {
  const Scene base = load();  // as written, <shadowrayepsilon> included: a length, unchanged by a move
  const Image expected = testing::renderChecked(base, defaultAccel()).image;
  for (double distance : {1e3, 1e5, 1e6})
    for (int axis = 0; axis < 3; ++axis) {
      Scene moved = base;
      glm::dvec3 offset(0.0);
      offset[axis] = distance;
      testing::translateScene(moved, offset);
      char what[32];
      std::snprintf(what, sizeof what, "moved %g along %c", distance, "xyz"[axis]);
      expectSame(testing::renderChecked(moved, defaultAccel()).image, expected, what);
    }
}

GTEST_ALLOW_UNINSTANTIATED_PARAMETERIZED_TEST(ScaleInvariance);
GTEST_ALLOW_UNINSTANTIATED_PARAMETERIZED_TEST(TranslationInvariance);
INSTANTIATE_TEST_SUITE_P(Conformance, ScaleInvariance, ::testing::ValuesIn(testing::conformanceScenePaths()),
                         [](const auto& info) { return info.param.stem().string(); });
INSTANTIATE_TEST_SUITE_P(Conformance, TranslationInvariance, ::testing::ValuesIn(testing::conformanceScenePaths()),
                         [](const auto& info) { return info.param.stem().string(); });

// ---- Shadow acne -------------------------------------------------------------------------------------

class EveryBackEnd : public ::testing::TestWithParam<AccelKind> {
 protected:
  void SetUp() override {
    if (availableAccel(GetParam()) != GetParam()) GTEST_SKIP() << "built without " << accelName(GetParam());
  }
};

class ShadowAcne : public EveryBackEnd {};

TEST_P(ShadowAcne, GrazingLightDownToATenthOfADegreeAtScales1eMinus4To1e4) {
  constexpr int kPixels = 48;
  constexpr double kShadowedBelow = 0.5;      // a pixel under half its lit value is self-shadowed
  constexpr double kRelativeTolerance = 1e-2;  // and a lit pixel is within 1 % of the exact value
  long pixels = 0, shadowed = 0, off = 0;
  double worst = 0.0;
  for (double scale : {1e-4, 1e-2, 1.0, 1e2, 1e4})
    for (double elevation : {30.0, 5.0, 1.0, 0.3, 0.1}) {
      const testing::GrazingLightScene s = testing::grazingLightScene(scale, elevation, kPixels);
      const auto prepared = prepareGeometry(s.scene, GetParam(), BvhBuild::Interactive);
      const Tracer tracer(s.scene, *prepared, RenderSettings{});
      long here = 0;
      for (int j = 0; j < kPixels; ++j)
        for (int i = 0; i < kPixels; ++i) {
          const double expected = testing::expectedGrazingRadiance(s, i, j);
          ASSERT_GT(expected, 0.0) << "the test scene must show the lit plane everywhere";
          RayCounts counts;
          const double actual = tracer.tracePixel(i, j, counts).x;
          const double deviation = std::fabs(actual - expected) / expected;
          worst = std::max(worst, deviation);
          ++pixels;
          shadowed += actual < kShadowedBelow * expected;
          here += actual < kShadowedBelow * expected;
          off += deviation > kRelativeTolerance;
        }
      if (here > 0) std::printf("[ figures  ] scale %g, light %g degrees up: %ld self-shadowed pixels\n", scale, elevation, here);
    }
  std::printf("[ figures  ] %s: %ld pixels lit at 0.1 to 30 degrees, scales 1e-4 to 1e4: %ld self-shadowed, "
              "%ld off by more than 1 %%, largest deviation %.2e\n",
              accelName(GetParam()).c_str(), pixels, shadowed, off, worst);
  EXPECT_EQ(shadowed, 0);
  EXPECT_EQ(off, 0);
}

// ---- Degenerate input --------------------------------------------------------------------------------

class DegenerateInput : public EveryBackEnd {
 protected:
  // A lit matte quad filling the view of a 16 x 16 camera at the origin looking down -z.
  static Scene litQuad() {
    Scene scene;
    scene.camera = testing::frontCamera(16);
    scene.ambientLight = Color(20.0f);
    Material m = testing::plainMaterial();
    m.specular = Color(0.5f);
    m.phongExponent = 20.0f;
    scene.materials.push_back(m);
    testing::addQuadFacingZ(scene, -3, -3, 3, 3, -2, 0);
    PointLight light;
    light.id = "1";
    light.position = {0.5, 0.7, 0.0};
    light.intensity = Color(200.0f);
    scene.lights.of<PointLight>().push_back(light);
    return scene;
  }
  // Renders, prints and checks: every unclamped pixel finite, and the product's renderFrame completes an
  // image of the right size.
  testing::CheckedRender check(const Scene& scene, const char* what) const {
    static ThreadPool pool(2);
    const auto prepared = prepareGeometry(scene, GetParam(), BvhBuild::Interactive);
    Image frame;
    FrameStats stats;
    EXPECT_TRUE(renderFrame(Tracer(scene, *prepared, RenderSettings{}), scene.camera.width, scene.camera.height,
                            pool, frame, stats))
        << what;
    EXPECT_EQ(frame.width, scene.camera.width) << what;
    EXPECT_EQ(frame.height, scene.camera.height) << what;
    const testing::CheckedRender r = testing::renderChecked(scene, GetParam());
    std::printf("[ figures  ] %s %s: %ld of %d pixels not finite, %llu rays, %.1f ms\n", accelName(GetParam()).c_str(),
                what, r.nonFinitePixels, scene.camera.width * scene.camera.height,
                static_cast<unsigned long long>(r.rays.total()), r.ms);
    EXPECT_EQ(r.nonFinitePixels, 0) << what;
    EXPECT_EQ(r.image.width, scene.camera.width) << what;
    EXPECT_EQ(r.image.height, scene.camera.height) << what;
    return r;
  }
};

TEST_P(DegenerateInput, ZeroAreaRepeatedAndNonFiniteVertices) {
  Scene scene = litQuad();
  const double inf = INFINITY;
  testing::addTriangle(scene, {-1, -1, -1.5}, {0, 0, -1.5}, {1, 1, -1.5}, 0);  // collinear
  testing::addTriangle(scene, {0.5, -0.5, -1.5}, {0.5, -0.5, -1.5}, {1, 0, -1.5}, 0);  // repeated vertex
  testing::addTriangle(scene, {0.2, 0.2, -1.2}, {0.2, 0.2, -1.2}, {0.2, 0.2, -1.2}, 0);  // a point
  testing::addTriangle(scene, {-0.5, 0.5, -1.5}, {inf, 0.5, -1.5}, {-0.5, 1, -1.5}, 0);  // infinite
  testing::addTriangle(scene, {-0.5, -0.8, -1.5}, {NAN, 0, -1.5}, {0, -0.4, -1.5}, 0);     // NaN
  check(scene, "zero-area, repeated, infinite and NaN vertices");
}

TEST_P(DegenerateInput, VerticesAt1e30) {
  Scene scene = litQuad();
  testing::addTriangle(scene, {-1e30, -1e30, -3}, {1e30, -1e30, -3}, {0, 1e30, -3}, 0);  // behind the quad
  testing::addTriangle(scene, {-0.5, -0.5, -1.5}, {0.5, -0.5, -1.5}, {0, 1e30, -1.5}, 0);  // a sliver in view
  testing::addTriangle(scene, {0.3, 0.3, -1}, {0.6, 0.3, -1}, {1e30, 1e30, 1e30}, 0);
  check(scene, "vertices at 1e30");
}

TEST_P(DegenerateInput, PhongExponentsAndIntensities) {
  for (float exponent : {0.0f, 1e6f})
    for (float intensity : {0.0f, 1e30f}) {
      Scene scene = litQuad();
      scene.materials[0].phongExponent = exponent;
      scene.lights.of<PointLight>()[0].intensity = Color(intensity);
      PointLight grazing = scene.lights.of<PointLight>()[0];
      grazing.position = {0.0, 0.0, -1.999};  // almost on the quad: 1e30 / d^2 stays finite in float
      scene.lights.of<PointLight>().push_back(grazing);
      char what[64];
      std::snprintf(what, sizeof what, "phong exponent %g, intensity %g", exponent, intensity);
      check(scene, what);
    }
}

TEST_P(DegenerateInput, FacingMirrorsCostGrowsLinearlyWithDepth) {
  constexpr int kPixels = 8;
  double msAt1000 = 0.0;
  for (int depth : {100, 500, 1000}) {
    const Scene scene = testing::facingMirrorsScene(depth, kPixels);
    char what[48];
    std::snprintf(what, sizeof what, "facing mirrors, depth %d", depth);
    const testing::CheckedRender r = check(scene, what);
    // Every camera ray bounces `depth` times: reflection rays exactly pixels x depth, a linear cost.
    EXPECT_EQ(r.rays.reflection, static_cast<std::uint64_t>(kPixels * kPixels) * depth);
    EXPECT_EQ(r.rays.shadow, static_cast<std::uint64_t>(kPixels * kPixels) * (depth + 1));
    if (depth == 1000) msAt1000 = r.ms;
  }
  std::printf("[ figures  ] %s facing mirrors: %.2f us per bounce per pixel at depth 1000\n",
              accelName(GetParam()).c_str(), 1000.0 * msAt1000 / (kPixels * kPixels * 1000.0));
}

INSTANTIATE_TEST_SUITE_P(BothBackEnds, ShadowAcne, ::testing::Values(AccelKind::Embree, AccelKind::Packet, AccelKind::Reference),
                         [](const auto& info) { return accelName(info.param); });
INSTANTIATE_TEST_SUITE_P(BothBackEnds, DegenerateInput, ::testing::Values(AccelKind::Embree, AccelKind::Packet, AccelKind::Reference),
                         [](const auto& info) { return accelName(info.param); });

}  // namespace
}  // namespace rayview
