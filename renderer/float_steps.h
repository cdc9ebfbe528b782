#pragma once
// The neighbouring floats of a float, without a libm call: std::nextafter is an out-of-line call that
// showed as 10 % of a render's profile (two per ray). Same results as std::nextafter(x, +-INFINITY).

#include <algorithm>
#include <bit>
#include <cstdint>
#include <limits>

#include "simd4.h"

namespace rayview {

// The smallest float above x; x itself for +infinity and NaN.
inline float nextFloatUp(float x) {
  if (!(x < std::numeric_limits<float>::infinity())) return x;  // +inf, NaN
  if (x == 0.0f) return std::numeric_limits<float>::denorm_min();  // +0 and -0
  const std::uint32_t bits = std::bit_cast<std::uint32_t>(x);
  return std::bit_cast<float>(x > 0.0f ? bits + 1u : bits - 1u);
}

// The largest float below x; x itself for -infinity and NaN.
inline float nextFloatDown(float x) { return -nextFloatUp(-x); }

// The same for four floats at once (a packet's rays are filled four at a time): lane for lane, bit for bit.
inline Float4 nextFloatUp4(Float4 x) {
  using UInt4 = std::uint32_t __attribute__((vector_size(16)));  // unsigned: -0's bits less one wrap, as the scalar's
  const UInt4 bits = std::bit_cast<UInt4>(x);
  const Float4 zero{}, infinity = Float4{} + std::numeric_limits<float>::infinity();
  const UInt4 one = UInt4{} + 1u;
  UInt4 next = x > zero ? bits + one : bits - one;
  next = x == zero ? one : next;                             // the smallest denormal, for +0 and -0
  return std::bit_cast<Float4>(x < infinity ? next : bits);  // +inf and NaN stay
}

inline Float4 nextFloatDown4(Float4 x) { return -nextFloatUp4(-x); }

// A float traversal's interval ends, widened by 2^-20 of themselves and a float step: Embree's SSE4.2 packet kernel
// on an Intel Xeon culled a triangle hit 7e-15 before a ray's end (45.4) when the end was one float step out. The
// hits are then decided in double against the ray's own interval, so only what is visited changes.
inline constexpr float kIntervalWidening = 0x1p-20f;
inline float widenedFar(double t) { return nextFloatUp(static_cast<float>(t) * (1.0f + kIntervalWidening)); }
inline float widenedNear(double t) {
  return std::max(0.0f, nextFloatDown(static_cast<float>(t) * (1.0f - kIntervalWidening)));
}
inline Float4 widenedFar4(Float4 t) { return nextFloatUp4(t * (1.0f + kIntervalWidening)); }
inline Float4 widenedNear4(Float4 t) {
  const Float4 near = nextFloatDown4(t * (1.0f - kIntervalWidening)), zero{};
  return zero < near ? near : zero;
}

}  // namespace rayview
