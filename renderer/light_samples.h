#pragma once
// Deterministic sample points on a triangular light (SPEC section 5): N = 1 is the centroid; larger N are
// stratified (a Hammersley set, rotated per pixel), so the same pixel and N always give the same image.

#include <cmath>
#include <cstdint>

#include <glm/vec2.hpp>

namespace rayview {

// A well-mixed 32-bit hash (lowbias32).
inline std::uint32_t hash32(std::uint32_t x) {
  x ^= x >> 16;
  x *= 0x7feb352dU;
  x ^= x >> 15;
  x *= 0x846ca68bU;
  x ^= x >> 16;
  return x;
}

inline float radicalInverseBase2(std::uint32_t bits) {
  bits = (bits << 16u) | (bits >> 16u);
  bits = ((bits & 0x55555555u) << 1u) | ((bits & 0xAAAAAAAAu) >> 1u);
  bits = ((bits & 0x33333333u) << 2u) | ((bits & 0xCCCCCCCCu) >> 2u);
  bits = ((bits & 0x0F0F0F0Fu) << 4u) | ((bits & 0xF0F0F0F0u) >> 4u);
  bits = ((bits & 0x00FF00FFu) << 8u) | ((bits & 0xFF00FF00u) >> 8u);
  return static_cast<float>(bits) * 2.3283064365386963e-10f;
}

// Offset in [0, 1)^2 within a pixel of camera ray k of n (anti-aliasing): stratified in x, a radical inverse
// in y, rotated per pixel by `pixelSeed` so neighbouring pixels do not share a pattern. Deterministic.
inline glm::vec2 pixelSampleOffset(int k, int n, std::uint32_t pixelSeed) {
  const float r1 = static_cast<float>(hash32(pixelSeed ^ 0x68bc21ebU) >> 8) * (1.0f / 16777216.0f);
  const float r2 = static_cast<float>(hash32(pixelSeed ^ 0x02e5be93U) >> 8) * (1.0f / 16777216.0f);
  float a = (static_cast<float>(k) + 0.5f) / static_cast<float>(n) + r1;
  float b = radicalInverseBase2(static_cast<std::uint32_t>(k)) + r2;
  return {a - std::floor(a), b - std::floor(b)};
}

}  // namespace rayview
