// rayview's packet BVH (renderer/packet_bvh_accel.cpp) on the inputs that strain its build: triangles that all share
// one centroid, a scene whose floats are denormal, one with every triangle degenerate or non-finite. Each must build
// and answer, and where the answer is well defined (a ray through a triangle's middle) give it. Its agreement with
// Embree on real scenes is tests/packet_test.cpp's.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <memory>

#include "rayview/accel.h"
#include "support/scene_builder.h"

namespace rayview {
namespace {

std::unique_ptr<Accel> packetBvh(const Scene& scene) {
  std::unique_ptr<Accel> accel = buildAccel(scene, AccelKind::Packet, glm::dvec3(0.0));
  EXPECT_TRUE(accel);
  if (accel) {
    EXPECT_EQ(accel->kind(), AccelKind::Packet);
  }
  return accel;
}

Scene emptyScene() {
  Scene scene;
  scene.camera = testing::frontCamera(8);
  scene.materials.push_back(testing::plainMaterial());
  return scene;
}

// 64 copies of one quad: every centroid the same, so no split separates them (the build halves by index).
TEST(PacketBvh, TrianglesSharingOneCentroidBuildAndAreHit) {
  Scene scene = emptyScene();
  for (int k = 0; k < 64; ++k) testing::addQuadFacingZ(scene, -1, -1, 1, 1, -2, 0);
  const auto accel = packetBvh(scene);
  ASSERT_TRUE(accel);
  const auto hit = accel->closestHit(Ray{{0, 0, 0}, {0.1, 0.2, -1}, 0.0, INFINITY});
  ASSERT_TRUE(hit.has_value());
  EXPECT_DOUBLE_EQ(hit->t, 2.0);
  EXPECT_LT(hit->triangle, 2u);  // the tie rule: the lowest index of the duplicates
}

// Coordinates around 1e-40: denormal as floats, so the binning's extents and scales are at the edge of float
// range (a bin width that overflowed to infinity once gave a bin index far outside the bins).
TEST(PacketBvh, DenormalSceneBuildsAndIsHit) {
  Scene scene = emptyScene();
  for (int k = 0; k < 40; ++k) {
    const double x = (k % 8 - 4) * 1e-40, y = (k / 8 - 2) * 1e-40;
    testing::addQuadFacingZ(scene, x, y, x + 1e-40, y + 1e-40, -2e-40 - k * 1e-45, 0);
  }
  const auto accel = packetBvh(scene);
  ASSERT_TRUE(accel);
  // Toward the middle of the first quad (x, y in [-4e-40, -3e-40]).
  const auto hit = accel->closestHit(Ray{{0, 0, 0}, {-3.5, -1.5, -2}, 0.0, INFINITY});
  ASSERT_TRUE(hit.has_value());
  EXPECT_LT(hit->triangle, 2u);
}

// Degenerate (zero-area) and non-finite triangles only: a BVH that no ray hits, and no crash.
TEST(PacketBvh, OnlyDegenerateAndNonFiniteTrianglesAnswerNoHit) {
  Scene scene = emptyScene();
  testing::addTriangle(scene, {0, 0, -1}, {0, 0, -1}, {0, 0, -1}, 0);
  testing::addTriangle(scene, {-1, 0, -1}, {1, 0, -1}, {3, 0, -1}, 0);
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  testing::addTriangle(scene, {nan, 0, -1}, {1, 0, -1}, {0, 1, -1}, 0);
  testing::addTriangle(scene, {inf, 0, -1}, {1, 0, -1}, {0, 1, -1}, 0);
  const auto accel = packetBvh(scene);
  ASSERT_TRUE(accel);
  for (const glm::dvec3 d : {glm::dvec3(0, 0, -1), glm::dvec3(0.5, 0.1, -1), glm::dvec3(1, 0, -1)}) {
    EXPECT_FALSE(accel->closestHit(Ray{{0, 0, 0}, d, 0.0, INFINITY}).has_value());
    EXPECT_FALSE(accel->occluded(Ray{{0, 0, 0}, d, 0.0, 10.0}));
  }
}

}  // namespace
}  // namespace rayview
