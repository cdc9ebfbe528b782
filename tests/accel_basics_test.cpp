// Ray-triangle intersection at the edges: shared edges and vertices, parallel rays, both back-ends.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>

#include "float_steps.h"
#include "rayview/accel.h"
#include "support/scene_builder.h"

namespace rayview {
namespace {

class AccelBasics : public ::testing::TestWithParam<AccelKind> {
 protected:
  void SetUp() override {
    if (availableAccel(GetParam()) != GetParam()) GTEST_SKIP() << "built without " << toString(GetParam());
    scene_.camera = testing::frontCamera(3);
    scene_.materials.push_back(testing::plainMaterial());
    testing::addQuadFacingZ(scene_, -1, -1, 1, 1, -2, 0);  // diagonal from (-1,-1) to (1,1)
    accel_ = buildAccel(scene_, GetParam(), glm::dvec3(0.0));
  }
  std::optional<Hit> shoot(glm::vec3 origin, glm::vec3 direction) const {
    return accel_->closestHit(Ray{origin, direction, 0.0f, INFINITY});
  }
  Scene scene_;
  std::unique_ptr<Accel> accel_;
};

TEST_P(AccelBasics, HitsTheInteriorWithDistanceAndBarycentrics) {
  auto hit = shoot({0.5f, -0.5f, 0.0f}, {0, 0, -1});
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->t, 2.0f, 1e-6f);
  EXPECT_EQ(hit->triangle, 0u);
  // Triangle 0 is (-1,-1), (1,-1), (1,1): (0.5,-0.5) = 0.25 a + 0.5 b + 0.25 c.
  EXPECT_NEAR(hit->b1, 0.5f, 1e-6f);
  EXPECT_NEAR(hit->b2, 0.25f, 1e-6f);
}

TEST_P(AccelBasics, SharedDiagonalNeverLeaks) {
  for (int k = -100; k <= 100; ++k) {
    const float s = k / 101.0f;
    EXPECT_TRUE(shoot({s, s, 0.0f}, {0, 0, -1})) << "leak at " << s;
    EXPECT_TRUE(shoot({0, 0, 0}, {s, s, -2.0f})) << "leak on a slanted ray at " << s;
  }
}

TEST_P(AccelBasics, SharedVerticesAndOuterEdgesHit) {
  EXPECT_TRUE(shoot({-1, -1, 0}, {0, 0, -1}));
  EXPECT_TRUE(shoot({1, 1, 0}, {0, 0, -1}));
  EXPECT_TRUE(shoot({1, -1, 0}, {0, 0, -1}));
  EXPECT_TRUE(shoot({0, -1, 0}, {0, 0, -1}));
}

TEST_P(AccelBasics, OutsideAndParallelRaysMiss) {
  EXPECT_FALSE(shoot({1.001f, 0, 0}, {0, 0, -1}));
  EXPECT_FALSE(shoot({-5, 0, -2}, {1, 0, 0}));  // in the plane of the quad
  EXPECT_FALSE(shoot({-5, 0, -1}, {1, 0, 0}));  // parallel, above it
  EXPECT_FALSE(shoot({0, 0, -3}, {0, 0, -1}));  // behind the origin
}

TEST_P(AccelBasics, OcclusionRespectsTheInterval) {
  EXPECT_TRUE(accel_->occluded(Ray{{0, 0, 0}, {0, 0, -1}, 0.0f, 3.0f}));
  EXPECT_FALSE(accel_->occluded(Ray{{0, 0, 0}, {0, 0, -1}, 0.0f, 1.9f}));
  EXPECT_FALSE(accel_->occluded(Ray{{0, 0, 0}, {0, 0, 1}, 0.0f, INFINITY}));
}

TEST_P(AccelBasics, CoordinatesAreRelativeToTheOrigin) {
  auto shifted = buildAccel(scene_, GetParam(), glm::dvec3(0, 0, -1));
  auto hit = shifted->closestHit(Ray{{0.5f, -0.5f, 1.0f}, {0, 0, -1}, 0.0f, INFINITY});
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->t, 2.0f, 1e-6f);
}

INSTANTIATE_TEST_SUITE_P(BothBackEnds, AccelBasics, ::testing::Values(AccelKind::Embree, AccelKind::Packet, AccelKind::Reference),
                         [](const auto& info) { return std::string(toString(info.param)); });

}  // namespace
}  // namespace rayview

namespace rayview {
namespace {

// The bit-step neighbours agree with std::nextafter everywhere it matters for ray intervals.
TEST(FloatSteps, AgreeWithNextafter) {
  const float values[] = {0.0f, -0.0f, 1.0f, -1.0f, 1e-40f, -1e-40f, 3.4e38f, -3.4e38f,
                          std::numeric_limits<float>::max(), std::numeric_limits<float>::lowest(),
                          std::numeric_limits<float>::denorm_min(), std::numeric_limits<float>::infinity(),
                          -std::numeric_limits<float>::infinity(), 123.456f, -0.001f};
  for (float v : values) {
    EXPECT_EQ(std::bit_cast<std::uint32_t>(nextFloatUp(v)),
              std::bit_cast<std::uint32_t>(std::nextafter(v, std::numeric_limits<float>::infinity())))
        << v;
    EXPECT_EQ(std::bit_cast<std::uint32_t>(nextFloatDown(v)),
              std::bit_cast<std::uint32_t>(std::nextafter(v, -std::numeric_limits<float>::infinity())))
        << v;
  }
  EXPECT_TRUE(std::isnan(nextFloatUp(std::numeric_limits<float>::quiet_NaN())));
}

// A float traversal's interval holds the double one with room to spare (2^-20 of each end and a float step: less
// let Embree's SSE4.2 packets on an Intel Xeon cull a hit 7e-15 before a ray's end), never below 0, infinity kept;
// four at a time lane for lane as one at a time.
TEST(FloatSteps, WidenedIntervalsHoldTheDoubleOnesWithRoom) {
  const double ends[] = {0.0, 1e-30, 1e-7, 0.5, 1.0, 45.379392531163361, 1e6, 3e38, INFINITY};
  for (double t : ends) {
    const float far = widenedFar(t), near = widenedNear(t);
    EXPECT_GE(static_cast<double>(far), t * (1.0 + 0x1p-21)) << t;
    if (t < INFINITY) {
      EXPECT_GT(static_cast<double>(far), t) << t;
    }
    if (t > 0.0 && t < INFINITY) {
      EXPECT_LE(static_cast<double>(near), t * (1.0 - 0x1p-21)) << t;
    }
    EXPECT_GE(near, 0.0f) << t;
  }
  EXPECT_EQ(widenedFar(INFINITY), INFINITY);
  EXPECT_EQ(widenedNear(0.0), 0.0f);
  EXPECT_EQ(std::bit_cast<std::uint32_t>(widenedNear(0.0)), 0u) << "+0, not -0";
  const Float4 x{0.0f, 45.3793945f, 1e-30f, INFINITY};
  const Float4 far4 = widenedFar4(x), near4 = widenedNear4(x);
  for (int j = 0; j < 4; ++j) {
    EXPECT_EQ(std::bit_cast<std::uint32_t>(far4[j]), std::bit_cast<std::uint32_t>(widenedFar(x[j]))) << x[j];
    EXPECT_EQ(std::bit_cast<std::uint32_t>(near4[j]), std::bit_cast<std::uint32_t>(widenedNear(x[j]))) << x[j];
  }
}

// The four-wide steps (a packet's rays are filled four at a time) give each lane the scalar step's bits.
TEST(FloatSteps, FourWideAgreeWithTheScalarSteps) {
  const float values[] = {0.0f, -0.0f, 1.0f, -1.0f, 1e-40f, -1e-40f, 3.4e38f, -3.4e38f,
                          std::numeric_limits<float>::max(), std::numeric_limits<float>::lowest(),
                          std::numeric_limits<float>::denorm_min(), std::numeric_limits<float>::infinity(),
                          -std::numeric_limits<float>::infinity(), std::numeric_limits<float>::quiet_NaN(),
                          123.456f, -0.001f};
  constexpr int kCount = sizeof values / sizeof values[0];
  static_assert(kCount % 4 == 0);
  for (int first = 0; first < kCount; first += 4) {
    // Each value in every lane position.
    for (int shift = 0; shift < 4; ++shift) {
      Float4 x;
      for (int j = 0; j < 4; ++j) x[j] = values[first + (j + shift) % 4];
      const Float4 up = nextFloatUp4(x), down = nextFloatDown4(x);
      for (int j = 0; j < 4; ++j) {
        EXPECT_EQ(std::bit_cast<std::uint32_t>(up[j]), std::bit_cast<std::uint32_t>(nextFloatUp(x[j]))) << x[j];
        EXPECT_EQ(std::bit_cast<std::uint32_t>(down[j]), std::bit_cast<std::uint32_t>(nextFloatDown(x[j]))) << x[j];
      }
    }
  }
}

}  // namespace
}  // namespace rayview
