// The specular term's power without libm (renderer/specular_power.h): whole exponents correctly rounded,
// everything else exactly std::pow.
#include "specular_power.h"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <random>

namespace rayview {
namespace {

float correctlyRounded(float x, float exponent) {
  return static_cast<float>(std::pow(static_cast<long double>(x), static_cast<long double>(exponent)));
}

TEST(SpecularPower, WholeExponentsAreCorrectlyRounded) {
  std::mt19937 random(7);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  long offByOneUlpFromPowf = 0, checked = 0;
  for (float exponent : {0.0f, 1.0f, 2.0f, 3.0f, 7.0f, 10.0f, 32.0f, 50.0f, 100.0f, 128.0f, 333.0f, 1000.0f, 4096.0f}) {
    for (int i = 0; i < 40000; ++i) {
      // Uniform in [0, 1], and crowded just below 1 where a high power is still visible.
      const float x = i % 2 ? unit(random) : 1.0f - 0.01f * unit(random);
      const float ours = specularPower(x, exponent);
      ASSERT_EQ(std::bit_cast<std::uint32_t>(ours), std::bit_cast<std::uint32_t>(correctlyRounded(x, exponent)))
          << x << "^" << exponent;
      const float libm = std::pow(x, exponent);
      ASSERT_LE(std::abs(static_cast<std::int64_t>(std::bit_cast<std::uint32_t>(ours)) -
                         static_cast<std::int64_t>(std::bit_cast<std::uint32_t>(libm))),
                1)
          << x << "^" << exponent;
      offByOneUlpFromPowf += ours != libm;
      ++checked;
    }
  }
  // powf itself is the one that is off; this is what the images can differ in (docs/numerics.md).
  EXPECT_LT(offByOneUlpFromPowf, checked / 100);
}

TEST(SpecularPower, EdgesAsStdPow) {
  EXPECT_EQ(specularPower(0.0f, 0.0f), 1.0f);
  EXPECT_EQ(specularPower(0.0f, 5.0f), 0.0f);
  EXPECT_EQ(specularPower(1.0f, 4096.0f), 1.0f);
  EXPECT_EQ(specularPower(0.5f, 200.0f), correctlyRounded(0.5f, 200.0f));  // underflows to a subnormal
  EXPECT_EQ(specularPower(1e-3f, 100.0f), 0.0f);                          // underflows to zero
  // Not whole or out of range: std::pow's answer, bit for bit.
  for (float exponent : {0.5f, 2.25f, 99.9f, -1.0f, -3.0f, 5000.0f, 1e9f}) {
    for (float x : {0.0f, 1e-6f, 0.25f, 0.9999f, 1.0f}) {
      const float expected = std::pow(x, exponent);
      EXPECT_EQ(std::bit_cast<std::uint32_t>(specularPower(x, exponent)), std::bit_cast<std::uint32_t>(expected))
          << x << "^" << exponent;
    }
  }
}

// Four (x, exponent) pairs at once (point-light shading, point_light_lanes.h) give each lane specularPower's bits:
// whole exponents of different bit lengths side by side, zero, and the std::pow ones (not whole, negative, too
// large) mixed into the same four.
TEST(SpecularPower, FourAtOnceAsOneAtATime) {
  std::mt19937 random(3);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  const float exponents[] = {0.0f, 1.0f, 2.0f, 3.0f, 20.0f, 60.0f, 100.0f, 500.0f, 1000.0f, 4095.0f, 4096.0f,
                             0.5f, 2.25f, 99.9f, -1.0f, -3.0f, 4097.0f, 5000.0f, 1e9f};
  constexpr int kExponents = sizeof exponents / sizeof exponents[0];
  std::uniform_int_distribution<int> pick(0, kExponents - 1);
  for (int block = 0; block < 20000; ++block) {
    Float4 x, e;
    for (int j = 0; j < 4; ++j) {
      x[j] = block % 5 == 0 ? 0.0f : (block % 7 == 0 ? 1.0f : unit(random));
      e[j] = exponents[pick(random)];
    }
    const Float4 four = specularPower4(x, e);
    for (int j = 0; j < 4; ++j)
      ASSERT_EQ(std::bit_cast<std::uint32_t>(four[j]), std::bit_cast<std::uint32_t>(specularPower(x[j], e[j])))
          << x[j] << "^" << e[j] << " in lane " << j;
  }
}

}  // namespace
}  // namespace rayview
