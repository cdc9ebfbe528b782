// Embree against the reference BVH on every conformance scene: random rays, same closest triangle except
// documented ties, hit distances within a stated tolerance.
//
// Rays (deterministic seed): half from the camera toward uniform points of the scene's bounding box, half
// between two uniform points of the box (as a closest-hit ray, and as an occlusion segment between them).
//
// Outcomes of a closest-hit ray:
//   agree      same miss, or same triangle with |tEmbree - tReference| <= tolerance(t);
//   tie        different triangles hit within tolerance(t) of each other: a shared edge or vertex, or
//              coplanar overlapping triangles; either answer is right;
//   rounding   a disagreement that the reference test itself reproduces on Embree's input: Embree works on
//              the vertices rounded to float (relative to the camera), and a ray that grazes a silhouette
//              edge by less than that rounding can hit in one geometry and miss in the other. Checked by
//              running the watertight test in double on the float-rounded vertices of the triangles
//              involved: Embree's triangle must be hit there at Embree's distance, and the reference's
//              triangle must be missed there (or hit no closer);
//   unexplained  anything else: must be zero.
// tolerance(t) = kRelativeTolerance * t + kScaleTolerance * sceneScale, sceneScale the largest coordinate
// magnitude of the scene relative to the camera (what Embree's float rounding is relative to).
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <thread>
#include <utility>
#include <vector>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include "accel_backends.h"
#include "rayview/accel.h"
#include "rayview/build_features.h"
#include "rayview/scene_loader.h"
#include "support/image_compare.h"
#include "support/conformance_scenes.h"
#include "watertight_triangle.h"

namespace rayview {
namespace {

constexpr std::uint64_t kSeed = 0x5eed477aULL;
constexpr int kRaysPerScene = 200000;  // x 16 scenes = 3.2 M closest-hit rays, plus 1.6 M occlusion segments
constexpr double kRelativeTolerance = 1e-5;
constexpr double kScaleTolerance = 1e-6;

// SplitMix64: the same numbers on every platform and standard library.
class Random {
 public:
  explicit Random(std::uint64_t seed) : state_(seed) {}
  double uniform() {
    std::uint64_t z = (state_ += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return static_cast<double>((z ^ (z >> 31)) >> 11) * 0x1p-53;
  }

 private:
  std::uint64_t state_;
};

std::uint64_t fnv1a(const std::string& text) {
  std::uint64_t h = 0xcbf29ce484222325ULL;
  for (unsigned char c : text) h = (h ^ c) * 0x100000001b3ULL;
  return h;
}

struct Tally {
  long rays = 0, agree = 0, ties = 0, rounding = 0, unexplained = 0;
  long roundingDistance = 0;  // of `rounding`: same triangle, distance beyond tolerance
  long segments = 0, occlusionAgree = 0, occlusionRounding = 0, occlusionUnexplained = 0;
  double maxRelativeError = 0.0;  // |tEmbree - tReference| / t, same-triangle hits at t >= sceneScale / 100
  double maxToleranceUse = 0.0;   // |tEmbree - tReference| / tolerance(t), same-triangle hits
};

class Agreement {
 public:
  Agreement(const Scene& scene, const Accel& embree, const Accel& reference)
      : scene_(scene), embree_(embree), reference_(reference) {
    const glm::dvec3 origin = reference.origin();
    for (const glm::dvec3& v : scene.vertices) {
      exact_.push_back(v - origin);
      rounded_.push_back(glm::dvec3(glm::vec3(v - origin)));  // what Embree is given
      lower_ = glm::min(lower_, v);
      upper_ = glm::max(upper_, v);
      sceneScale_ = std::max(sceneScale_, std::max({std::fabs(v.x - origin.x), std::fabs(v.y - origin.y),
                                                    std::fabs(v.z - origin.z)}));
    }
  }

  const glm::dvec3& lower() const { return lower_; }
  const glm::dvec3& upper() const { return upper_; }

  double tolerance(double t) const { return kRelativeTolerance * t + kScaleTolerance * sceneScale_; }

  void closestHit(const Ray& ray, Tally& tally) {
    ++tally.rays;
    const std::optional<Hit> e = embree_.closestHit(ray), r = reference_.closestHit(ray);
    if (!e && !r) {
      ++tally.agree;
      return;
    }
    if (e && r && e->triangle == r->triangle) {
      const double error = std::fabs(double(e->t) - double(r->t));
      if (r->t >= 0.01 * sceneScale_) tally.maxRelativeError = std::max(tally.maxRelativeError, error / r->t);
      tally.maxToleranceUse = std::max(tally.maxToleranceUse, error / tolerance(r->t));
      if (error <= tolerance(r->t)) {
        ++tally.agree;
        return;
      }
      if (explainedByRounding(ray, e, r)) {
        ++tally.rounding;
        ++tally.roundingDistance;
        return;
      }
    } else if (e && r && std::fabs(double(e->t) - double(r->t)) <= tolerance(r->t)) {
      ++tally.ties;
      return;
    }
    if (explainedByRounding(ray, e, r)) {
      ++tally.rounding;
    } else {
      ++tally.unexplained;
      if (tally.unexplained <= 5) report(ray, e, r);
    }
  }

  void occlusion(const Ray& segment, Tally& tally) {
    ++tally.segments;
    const bool e = embree_.occluded(segment), r = reference_.occluded(segment);
    if (e == r) {
      ++tally.occlusionAgree;
      return;
    }
    // Explained when the nearest hit lies within tolerance of the segment's end or start, or when the
    // closest-hit answers themselves differ only by rounding.
    Ray open = segment;
    open.tFar = INFINITY;
    const std::optional<Hit> ce = embree_.closestHit(open), cr = reference_.closestHit(open);
    const double end = segment.tFar;
    auto nearEnd = [&](const std::optional<Hit>& h) { return h && std::fabs(h->t - end) <= tolerance(end); };
    if (nearEnd(ce) || nearEnd(cr) || explainedByRounding(open, ce, cr)) {
      ++tally.occlusionRounding;
    } else {
      ++tally.occlusionUnexplained;
    }
  }

 private:
  // The watertight test in double on one triangle, with its exact or float-rounded vertices.
  std::optional<double> test(const Ray& ray, std::uint32_t triangle, bool rounded) const {
    const SceneArray<glm::dvec3>& v = rounded ? rounded_ : exact_;
    const Triangle& t = scene_.triangles[triangle];
    const WatertightRay w = prepareWatertightRay(glm::dvec3(ray.origin), glm::dvec3(ray.direction));
    TriangleHit hit;
    if (!intersectWatertight(w, v[t.vertex[0]], v[t.vertex[1]], v[t.vertex[2]], ray.tNear, INFINITY, hit))
      return std::nullopt;
    return hit.t;
  }

  bool explainedByRounding(const Ray& ray, const std::optional<Hit>& e, const std::optional<Hit>& r) const {
    if (e) {
      const std::optional<double> t = test(ray, e->triangle, true);
      if (!t || std::fabs(*t - e->t) > tolerance(e->t)) return false;
    }
    if (r) {
      const std::optional<double> t = test(ray, r->triangle, true);
      if (t && (!e || *t < e->t - tolerance(e->t))) return false;
    }
    return true;
  }

  void report(const Ray& ray, const std::optional<Hit>& e, const std::optional<Hit>& r) const {
    auto describe = [](const std::optional<Hit>& h) {
      char text[96];
      if (!h) return std::string("miss");
      std::snprintf(text, sizeof text, "triangle %u at t=%.9g (b1 %.6g, b2 %.6g)", h->triangle, h->t, h->b1, h->b2);
      return std::string(text);
    };
    ADD_FAILURE() << "unexplained disagreement: ray from (" << ray.origin.x << ", " << ray.origin.y << ", "
                  << ray.origin.z << ") along (" << ray.direction.x << ", " << ray.direction.y << ", "
                  << ray.direction.z << "): Embree " << describe(e) << ", reference " << describe(r);
  }

  const Scene& scene_;
  const Accel& embree_;
  const Accel& reference_;
  SceneArray<glm::dvec3> exact_, rounded_;
  glm::dvec3 lower_{INFINITY}, upper_{-INFINITY};
  double sceneScale_ = 0.0;
};

class AccelAgreement : public ::testing::TestWithParam<std::filesystem::path> {
 public:
  static void TearDownTestSuite() {
    if (total.rays == 0) return;
    std::printf("[ figures  ] all scenes: %ld rays, %.4f %% agree, %ld ties, %ld rounding, %ld unexplained; "
                "%ld segments, %ld unexplained occlusion answers\n",
                total.rays, 100.0 * total.agree / total.rays, total.ties, total.rounding, total.unexplained,
                total.segments, total.occlusionUnexplained);
  }
  static inline Tally total;  // over the scenes run in this process
};

TEST_P(AccelAgreement, SameClosestTriangleAndDistance) {
  if (availableAccel(AccelKind::Embree) != AccelKind::Embree) GTEST_SKIP() << "built without Embree";
  const auto start = std::chrono::steady_clock::now();
  const Scene scene = loadSceneFile(GetParam()).scene;
  const glm::dvec3 origin = scene.camera.position;
  const std::unique_ptr<Accel> embree = buildAccel(scene, AccelKind::Embree, origin);
  const std::unique_ptr<Accel> reference = buildAccel(scene, AccelKind::Reference, origin);
  ASSERT_TRUE(embree && reference);
  Agreement agreement(scene, *embree, *reference);

  Random random(kSeed ^ fnv1a(GetParam().filename().string()));
  auto pointInBox = [&] {
    const glm::dvec3 f(random.uniform(), random.uniform(), random.uniform());
    return agreement.lower() + f * (agreement.upper() - agreement.lower()) - origin;
  };
  Tally tally;
  for (int k = 0; k < kRaysPerScene; ++k) {
    const bool fromCamera = k % 2 == 0;
    const glm::dvec3 a = fromCamera ? glm::dvec3(0.0) : pointInBox();
    const glm::dvec3 b = pointInBox();
    const double length = glm::length(b - a);
    if (!(length > 0.0)) continue;
    const Ray ray{glm::vec3(a), glm::vec3((b - a) / length), 0.0f, INFINITY};
    agreement.closestHit(ray, tally);
    if (!fromCamera) agreement.occlusion(Ray{ray.origin, ray.direction, 0.0f, static_cast<float>(length)}, tally);
  }

  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("[ figures  ] %s: %ld rays, %.4f %% agree, %ld ties, %ld rounding (%ld of them distance only), "
              "%ld unexplained; max |dt|/t %.1e, max |dt| %.2f x tolerance; %ld segments: %ld occlusion answers "
              "differ (%ld rounding, %ld unexplained); %.1f s\n",
              GetParam().stem().string().c_str(), tally.rays, 100.0 * tally.agree / tally.rays, tally.ties,
              tally.rounding, tally.roundingDistance, tally.unexplained, tally.maxRelativeError, tally.maxToleranceUse,
              tally.segments, tally.segments - tally.occlusionAgree, tally.occlusionRounding,
              tally.occlusionUnexplained, seconds);
  total.rays += tally.rays;
  total.agree += tally.agree;
  total.ties += tally.ties;
  total.rounding += tally.rounding;
  total.unexplained += tally.unexplained;
  total.segments += tally.segments;
  total.occlusionUnexplained += tally.occlusionUnexplained;
  EXPECT_EQ(tally.unexplained, 0);
  EXPECT_EQ(tally.occlusionUnexplained, 0);
  EXPECT_EQ(tally.agree + tally.ties + tally.rounding + tally.unexplained, tally.rays);
}

#ifdef RAYVIEW_HAVE_EMBREE
// Rays toward a random point of a random triangle of `scene`, from the origin (the camera) or from a random point
// of the scene's box; every fourth a segment ending there.
std::vector<Ray> raysAtTriangles(const Scene& scene, const glm::dvec3& origin, const std::string& name, int count) {
  glm::dvec3 lower(INFINITY), upper(-INFINITY);
  for (const glm::dvec3& v : scene.vertices) lower = glm::min(lower, v), upper = glm::max(upper, v);
  Random random(kSeed ^ fnv1a(name));
  std::vector<Ray> rays;
  for (int k = 0; k < count; ++k) {
    const Triangle& t = scene.triangles[static_cast<std::size_t>(random.uniform() * scene.triangles.size())];
    double u = random.uniform(), v = random.uniform();
    if (u + v > 1.0) u = 1.0 - u, v = 1.0 - v;
    const glm::dvec3 b = (1.0 - u - v) * scene.vertices[t.vertex[0]] + u * scene.vertices[t.vertex[1]] +
                         v * scene.vertices[t.vertex[2]] - origin;
    const glm::dvec3 a = k % 2 == 0 ? glm::dvec3(0.0) : lower + glm::dvec3(random.uniform(), random.uniform(),
                                                                             random.uniform()) * (upper - lower) - origin;
    const double length = glm::length(b - a);
    if (length > 0.0) rays.push_back(Ray{a, (b - a) / length, 0.0, k % 4 == 1 ? length : INFINITY});
  }
  return rays;
}

// `other` answers every ray as `base` does, bit for bit: packets of closest hits and of occlusion, and the single
// ray forms. Returns how many rays hit.
int expectSameAnswers(const Accel& base, const Accel& other, const std::vector<Ray>& rays, const std::string& name) {
  int hits = 0;
  for (std::size_t i = 0; i + kRayPacket <= rays.size(); i += kRayPacket) {
    std::optional<Hit> packetBase[kRayPacket], packetOther[kRayPacket];
    base.closestHits(&rays[i], kRayPacket, packetBase);
    other.closestHits(&rays[i], kRayPacket, packetOther);
    bool occludedBase[kRayPacket], occludedOther[kRayPacket];
    base.occludedMany(&rays[i], kRayPacket, occludedBase);
    other.occludedMany(&rays[i], kRayPacket, occludedOther);
    for (int k = 0; k < kRayPacket; ++k) {
      const Ray& ray = rays[i + k];
      const std::optional<Hit> single = other.closestHit(ray);
      for (const std::optional<Hit>* answer : {&std::as_const(packetOther[k]), &single}) {
        EXPECT_EQ(answer->has_value(), packetBase[k].has_value()) << name << " ray " << i + k;
        if (!packetBase[k] || !answer->has_value()) continue;
        EXPECT_EQ((*answer)->triangle, packetBase[k]->triangle) << name << " ray " << i + k;
        EXPECT_EQ((*answer)->t, packetBase[k]->t) << name << " ray " << i + k;
        EXPECT_EQ((*answer)->b1, packetBase[k]->b1) << name << " ray " << i + k;
        EXPECT_EQ((*answer)->b2, packetBase[k]->b2) << name << " ray " << i + k;
      }
      hits += packetBase[k].has_value();
      EXPECT_EQ(occludedOther[k], occludedBase[k]) << name << " ray " << i + k;
      EXPECT_EQ(other.occluded(ray), occludedBase[k]) << name << " ray " << i + k;
    }
    if (::testing::Test::HasFailure()) break;  // one packet's failures say enough
  }
  return hits;
}

// Embree's BVH layouts (the compact one is what scenes from kCompactBvhTriangles get, the quick build what a render
// with few rays a triangle gets) give the same answers,
// bit for bit: every hit is the closest by the watertight test and the tie rule, whatever order the BVH visits the
// triangles in. Single rays and packets, closest hits and occlusion.
TEST(EmbreeLayouts, TheCompactLayoutGivesTheSameAnswersBitForBit) {
  RAYVIEW_SKIP_WITHOUT_SHARED();
  if (availableAccel(AccelKind::Embree) != AccelKind::Embree) GTEST_SKIP() << "built without Embree";
  ASSERT_EQ(embreeLayoutFor(kCompactBvhTriangles - 1), EmbreeLayout::Fast);
  ASSERT_EQ(embreeLayoutFor(kCompactBvhTriangles), EmbreeLayout::Compact);
  int scenes = 0;
  for (const std::filesystem::path& path : testing::conformanceScenePaths()) {
    const std::string name = path.stem().string();
    if (name != "killeroo_2020" && name != "bunny" && name != "car") continue;
    ++scenes;
    const Scene scene = loadSceneFile(path).scene;
    const glm::dvec3 origin = scene.camera.position;
    const std::unique_ptr<Accel> fast = makeEmbreeAccel(scene, origin, EmbreeLayout::Fast, nullptr, nullptr);
    const std::unique_ptr<Accel> compact = makeEmbreeAccel(scene, origin, EmbreeLayout::Compact, nullptr, nullptr);
    const std::unique_ptr<Accel> quick = makeEmbreeAccel(scene, origin, EmbreeLayout::Quick, nullptr, nullptr);
    const std::unique_ptr<Accel> compactQuick =
        makeEmbreeAccel(scene, origin, EmbreeLayout::CompactQuick, nullptr, nullptr);
    ASSERT_TRUE(fast && compact && quick && compactQuick);
    const std::vector<Ray> rays = raysAtTriangles(scene, origin, name, 20000);
    EXPECT_GT(expectSameAnswers(*fast, *compact, rays, name), static_cast<int>(rays.size()) / 2)
        << name << ": the rays must mostly hit";
    EXPECT_GT(expectSameAnswers(*fast, *quick, rays, name + " (quick)"), static_cast<int>(rays.size()) / 2);
    EXPECT_GT(expectSameAnswers(*fast, *compactQuick, rays, name + " (compact quick)"),
              static_cast<int>(rays.size()) / 2);
  }
  EXPECT_EQ(scenes, 3);
}

// The quick build is for one render that casts few camera rays a triangle, never for the viewer (no pixels given),
// and past the compact layout's size it keeps that layout's memory (CompactQuick).
TEST(EmbreeLayouts, TheQuickBuildIsForRendersWithFewRaysATriangle) {
  EXPECT_EQ(embreeLayoutFor(92092), EmbreeLayout::Fast) << "no render given: the viewer's build";
  EXPECT_EQ(embreeLayoutFor(92092, 800 * 600), EmbreeLayout::Quick) << "killeroo_2020: ~5 rays a triangle";
  EXPECT_EQ(embreeLayoutFor(6619, 1024 * 768), EmbreeLayout::Fast) << "car: ~120 rays a triangle";
  EXPECT_EQ(embreeLayoutFor(kCompactBvhTriangles), EmbreeLayout::Compact) << "the viewer's build of a big scene";
  EXPECT_EQ(embreeLayoutFor(1'002'528, 1920 * 1080), EmbreeLayout::CompactQuick)
      << "the 1M height field: ~2 rays a triangle";
  EXPECT_EQ(embreeLayoutFor(kCompactBvhTriangles, kQuickBuildRaysPerTriangle * kCompactBvhTriangles),
            EmbreeLayout::Compact);
  EXPECT_EQ(embreeLayoutFor(1000, kQuickBuildRaysPerTriangle * 1000 - 1), EmbreeLayout::Quick);
  EXPECT_EQ(embreeLayoutFor(1000, kQuickBuildRaysPerTriangle * 1000), EmbreeLayout::Fast);
}

// Embree hands the callbacks a 16-ray packet whole on an AVX-512 machine, in halves with AVX2 and in quarters with
// SSE; the callbacks test the lanes four at a time by their ids (watertight_lanes.h). Devices limited to AVX2 and to
// SSE4.2 (which this machine can run whatever it has beyond them) give the answers of the default device bit for bit.
TEST(EmbreeIsas, EveryPacketWidthGivesTheSameAnswersBitForBit) {
  RAYVIEW_SKIP_WITHOUT_SHARED();
  if (availableAccel(AccelKind::Embree) != AccelKind::Embree) GTEST_SKIP() << "built without Embree";
  if (!__builtin_cpu_supports("avx2")) GTEST_SKIP() << "this machine has no AVX2";
  int scenes = 0;
  for (const std::filesystem::path& path : testing::conformanceScenePaths()) {
    const std::string name = path.stem().string();
    if (name != "killeroo_2020" && name != "car") continue;
    ++scenes;
    const Scene scene = loadSceneFile(path).scene;
    const glm::dvec3 origin = scene.camera.position;
    const std::unique_ptr<Accel> native = makeEmbreeAccel(scene, origin, EmbreeLayout::Fast, nullptr, nullptr);
    ASSERT_TRUE(native);
    const std::vector<Ray> rays = raysAtTriangles(scene, origin, name, 20000);
    for (const char* isa : {"avx2", "sse4.2"}) {
      const std::unique_ptr<Accel> narrow = makeEmbreeAccelForIsa(scene, origin, isa);
      ASSERT_TRUE(narrow) << isa;
      EXPECT_GT(expectSameAnswers(*native, *narrow, rays, name + " " + isa), static_cast<int>(rays.size()) / 2)
          << name << ": the rays must mostly hit";
    }
  }
  EXPECT_EQ(scenes, 2);
}

// A packet of fewer than 16 rays, the first a thread sends (its scratch lanes never filled), at every packet width:
// Embree's narrower traversals call back for lanes the valid mask leaves out unless their interval is empty, and the
// callbacks read those lanes' rays. Each answer must be the single ray's, and nothing read beyond the query's rays.
TEST(EmbreeIsas, PacketsOfFewRaysOnANewThreadAnswerOnlyTheirRays) {
  if (availableAccel(AccelKind::Embree) != AccelKind::Embree) GTEST_SKIP() << "built without Embree";
  if (!__builtin_cpu_supports("avx2")) GTEST_SKIP() << "this machine has no AVX2";
  SceneGeometry scene;
  scene.vertices = {{-1.0, -1.0, -2.0}, {1.0, -1.0, -2.0}, {0.0, 1.0, -2.0}};
  scene.addFace(Triangle{{0, 1, 2}});
  const glm::dvec3 origin{0.0};
  for (const char* isa : {"", "avx2", "sse4.2"}) {
    const std::unique_ptr<Accel> accel = *isa ? makeEmbreeAccelForIsa(scene, origin, isa)
                                              : makeEmbreeAccel(scene, origin, EmbreeLayout::Fast, nullptr, nullptr);
    ASSERT_TRUE(accel) << isa;
    for (int count = 1; count < kRayPacket; ++count) {
      std::vector<Ray> rays(static_cast<std::size_t>(count));
      for (int k = 0; k < count; ++k)
        rays[static_cast<std::size_t>(k)] = Ray{{0.0, 0.0, 0.0}, {0.01 * k, 0.0, -1.0}, 0.0, 10.0};
      std::optional<Hit> hits[kRayPacket];
      bool occluded[kRayPacket] = {};
      std::thread([&] {  // a new thread: its packet scratch holds no earlier query's lanes
        accel->closestHits(rays.data(), count, hits);
        accel->occludedMany(rays.data(), count, occluded);
      }).join();
      for (int k = 0; k < count; ++k) {
        const std::optional<Hit> single = accel->closestHit(rays[static_cast<std::size_t>(k)]);
        ASSERT_TRUE(single.has_value()) << isa << " ray " << k;
        ASSERT_TRUE(hits[k].has_value()) << isa << " count " << count << " ray " << k;
        EXPECT_EQ(hits[k]->t, single->t) << isa << " count " << count << " ray " << k;
        EXPECT_TRUE(occluded[k]) << isa << " count " << count << " ray " << k;
      }
    }
  }
}
#endif  // RAYVIEW_HAVE_EMBREE

GTEST_ALLOW_UNINSTANTIATED_PARAMETERIZED_TEST(AccelAgreement);
INSTANTIATE_TEST_SUITE_P(Conformance, AccelAgreement, ::testing::ValuesIn(testing::conformanceScenePaths()),
                         [](const auto& info) { return info.param.stem().string(); });

}  // namespace
}  // namespace rayview
