// The reference BVH on its own: same answers as testing every triangle, build progress and cancel,
// degenerate and empty input, and a build of a million triangles in a few seconds.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <vector>

#include "rayview/accel.h"
#include "support/test_meshes.h"
#include "watertight_triangle.h"

namespace rayview {
namespace {

class Lcg {
 public:
  double uniform() {
    state_ = state_ * 6364136223846793005ULL + 1442695040888963407ULL;
    return static_cast<double>(state_ >> 11) * 0x1p-53;
  }
  glm::dvec3 point(double size) { return size * glm::dvec3(uniform() - 0.5, uniform() - 0.5, uniform() - 0.5); }

 private:
  std::uint64_t state_ = 42;
};

// Random triangles of very different sizes, overlapping and crossing.
Scene triangleSoup(int count, Lcg& random) {
  Scene scene;
  scene.materials.push_back(Material{});
  for (int i = 0; i < count; ++i) {
    const glm::dvec3 centre = random.point(20.0);
    const double size = std::pow(10.0, -2.0 + 3.0 * random.uniform());
    const auto first = static_cast<std::uint32_t>(scene.vertices.size());
    for (int k = 0; k < 3; ++k) scene.vertices.push_back(centre + random.point(size));
    Triangle t;
    t.vertex[0] = first;
    t.vertex[1] = first + 1;
    t.vertex[2] = first + 2;
    scene.triangles.push_back(t);
  }
  return scene;
}

// The closest hit by testing every triangle, with the same watertight test and the same tie rule.
std::optional<Hit> bruteForce(const Scene& scene, const Ray& ray) {
  const WatertightRay w = prepareWatertightRay(ray.origin, ray.direction);
  std::optional<Hit> best;
  for (std::size_t i = 0; i < scene.triangles.size(); ++i) {
    const Triangle& t = scene.triangles[i];
    TriangleHit h;
    const auto id = static_cast<std::uint32_t>(i);
    if (intersectWatertight(w, scene.vertices[t.vertex[0]], scene.vertices[t.vertex[1]], scene.vertices[t.vertex[2]],
                            ray.tNear, ray.tFar, h) &&
        (!best || replacesClosestHit(h.t, id, best->t, best->triangle)))
      best = Hit{h.t, id, h.b1, h.b2};
  }
  return best;
}

TEST(ReferenceBvh, SameClosestHitAsTestingEveryTriangle) {
  Lcg random;
  const Scene scene = triangleSoup(4000, random);
  const auto accel = buildAccel(scene, AccelKind::Reference, glm::dvec3(0.0));
  ASSERT_TRUE(accel);
  int hits = 0;
  for (int k = 0; k < 10000; ++k) {
    const glm::dvec3 from = random.point(40.0), to = random.point(20.0);
    const Ray ray{from, to - from, 0.0, k % 3 == 0 ? 0.7 : INFINITY};
    const std::optional<Hit> expected = bruteForce(scene, ray), actual = accel->closestHit(ray);
    ASSERT_EQ(actual.has_value(), expected.has_value()) << "ray " << k;
    EXPECT_EQ(accel->occluded(ray), expected.has_value()) << "ray " << k;
    if (!expected) continue;
    ++hits;
    EXPECT_EQ(actual->t, expected->t) << "ray " << k;
    EXPECT_EQ(actual->triangle, expected->triangle) << "ray " << k;  // ties go to the lower index in both
  }
  std::printf("[ figures  ] %d of 10000 rays hit; all equal to testing every triangle\n", hits);
  EXPECT_GT(hits, 1000);
}

TEST(ReferenceBvh, ExcludedTriangleIsNeverReported) {
  Scene scene;
  scene.materials.push_back(Material{});
  testing::addTessellatedPlane(scene, testing::Placement{}, 1, 0);  // two triangles in z = 0
  const auto accel = buildAccel(scene, AccelKind::Reference, glm::dvec3(0.0));
  Ray ray{{0.5f, -0.5f, 1.0f}, {0, 0, -1}, 0.0f, INFINITY};
  const std::optional<Hit> hit = accel->closestHit(ray);
  ASSERT_TRUE(hit);
  ray.excludedTriangle = hit->triangle;
  EXPECT_FALSE(accel->closestHit(ray));
  EXPECT_FALSE(accel->occluded(ray));
}

TEST(ReferenceBvh, DegenerateAndEmptyInput) {
  Scene empty;
  const auto none = buildAccel(empty, AccelKind::Reference, glm::dvec3(0.0));
  ASSERT_TRUE(none);
  EXPECT_FALSE(none->closestHit(Ray{{0, 0, 0}, {0, 0, -1}, 0.0f, INFINITY}));

  Scene scene;
  scene.vertices = {{0, 0, -1}, {1, 0, -1}, {2, 0, -1}, {0, 1, -1}, {INFINITY, 0, -1}, {NAN, 1, -1}};
  for (auto [a, b, c] : {std::array<std::uint32_t, 3>{0, 1, 2}, {0, 0, 3}, {0, 1, 4}, {0, 1, 5}, {0, 1, 99}}) {
    Triangle t;
    t.vertex[0] = a;
    t.vertex[1] = b;
    t.vertex[2] = c;
    scene.triangles.push_back(t);
  }
  const auto accel = buildAccel(scene, AccelKind::Reference, glm::dvec3(0.0));
  ASSERT_TRUE(accel);
  for (glm::vec3 d : {glm::vec3(0.5f, 0.0f, -1.0f), glm::vec3(0.0f, 0.3f, -1.0f), glm::vec3(0.5f, 0.4f, -1.0f)})
    EXPECT_FALSE(accel->closestHit(Ray{{0, 0, 0}, d, 0.0f, INFINITY}));
  // Rays that cannot hit: zero, infinite or NaN direction, NaN interval.
  EXPECT_FALSE(accel->closestHit(Ray{{0, 0, 0}, {0, 0, 0}, 0.0f, INFINITY}));
  EXPECT_FALSE(accel->occluded(Ray{{0, 0, 0}, {NAN, 0, -1}, 0.0f, INFINITY}));
  EXPECT_FALSE(accel->occluded(Ray{{0, 0, 0}, {0.1f, 0.1f, -1}, NAN, INFINITY}));
}

struct ProgressLog {
  std::vector<double> fractions;
  double cancelAt = 2.0;  // cancel at the first report at or above this fraction
};

bool logProgress(void* user, double fraction) {
  auto* log = static_cast<ProgressLog*>(user);
  log->fractions.push_back(fraction);
  return fraction < log->cancelAt;
}

TEST(ReferenceBvh, ReportsProgressAndCancels) {
  Scene scene;
  scene.materials.push_back(Material{});
  testing::addTessellatedPlane(scene, testing::Placement{}, 100, 0);  // 20000 triangles

  ProgressLog complete;
  ASSERT_TRUE(buildAccel(scene, AccelKind::Reference, glm::dvec3(0.0), logProgress, &complete));
  ASSERT_GE(complete.fractions.size(), 10u);
  EXPECT_EQ(complete.fractions.front(), 0.0);
  EXPECT_EQ(complete.fractions.back(), 1.0);
  for (std::size_t i = 1; i < complete.fractions.size(); ++i) EXPECT_LE(complete.fractions[i - 1], complete.fractions[i]);

  ProgressLog beforeStart;
  beforeStart.cancelAt = 0.0;
  EXPECT_FALSE(buildAccel(scene, AccelKind::Reference, glm::dvec3(0.0), logProgress, &beforeStart));
  EXPECT_EQ(beforeStart.fractions.size(), 1u);

  ProgressLog midway;
  midway.cancelAt = 0.4;
  EXPECT_FALSE(buildAccel(scene, AccelKind::Reference, glm::dvec3(0.0), logProgress, &midway));
  EXPECT_LT(midway.fractions.back(), 1.0);
  EXPECT_LT(midway.fractions.size(), complete.fractions.size());
}

// Its times are printed for a reader; bench/ measures speed.
TEST(ReferenceBvh, BuildsAndTracesAMillionTriangles) {
  Scene scene;
  scene.materials.push_back(Material{});
  testing::addIcosphere(scene, testing::Placement{}, 8, 0);  // 20 * 4^8 = 1 310 720 triangles
  const auto start = std::chrono::steady_clock::now();
  const auto accel = buildAccel(scene, AccelKind::Reference, glm::dvec3(0.0, 0.0, 3.0));
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  ASSERT_TRUE(accel);
  Lcg random;
  int hits = 0;
  const auto traceStart = std::chrono::steady_clock::now();
  for (int k = 0; k < 100000; ++k) {
    const glm::dvec3 target = random.point(2.0);
    hits += accel->closestHit(Ray{{0, 0, 0}, glm::vec3(target - glm::dvec3(0, 0, 3)), 0.0f, INFINITY}).has_value();
  }
  const double traceSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - traceStart).count();
  std::printf("[ figures  ] %zu triangles: build %.2f s, %.2f M rays/s on one thread\n", scene.triangles.size(), seconds,
              0.1 / traceSeconds);
  EXPECT_GT(hits, 30000);
}

}  // namespace
}  // namespace rayview
