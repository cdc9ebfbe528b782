#pragma once
// The watertight test of watertight_triangle.h for four rays of a packet against one triangle at once.
//
// Embree calls a user geometry's callback once per triangle with a packet's lanes (13-16 of 16 valid on
// average in car, bunny, grid_large and mirror_scene), and a coherent packet's neighbouring rays nearly always
// share their axis permutation (97 % of the blocks of four in car, all but 0.1 % in the others). So the test
// runs on four lanes in vector registers (AVX2 when the build targets x86-64-v3, two SSE2 halves otherwise),
// with the permutation of the block known at compile time.
//
// Bit for bit what intersectWatertight gives each lane: the same IEEE operations on the same numbers in the
// same order, each rounded on its own (the build forbids contraction, CMakeLists.txt), so the tie rule and
// every numerics guarantee carry over. WatertightLanes.AgreeWithTheScalarTestBitForBit checks it.

#include <cstdint>
#include <cstring>

#include <glm/vec3.hpp>

#include "watertight_triangle.h"

namespace rayview {

inline constexpr int kWatertightWidth = 4;

// A packet's rays as the four-wide test reads them: one array per quantity, lane k at [k]. kLanes is a
// multiple of kWatertightWidth.
template <int kLanes>
struct WatertightLanes {
  static_assert(kLanes % kWatertightWidth == 0);
  alignas(32) double origin[3][kLanes] = {};
  alignas(32) double shearX[kLanes] = {};
  alignas(32) double shearY[kLanes] = {};
  alignas(32) double shearZ[kLanes] = {};
  alignas(32) double tNear[kLanes] = {};
  alignas(32) double tFar[kLanes] = {};
  int permutation[kLanes] = {};  // watertightPermutation of the lane's ray

  void set(int k, const WatertightRay& ray, double near, double far) {
    for (int axis = 0; axis < 3; ++axis) origin[axis][k] = ray.origin[axis];
    shearX[k] = ray.shearX;
    shearY[k] = ray.shearY;
    shearZ[k] = ray.shearZ;
    tNear[k] = near;
    tFar[k] = far;
    permutation[k] = watertightPermutation(ray);
  }
};

namespace watertight_detail {

using Double4 = double __attribute__((vector_size(32)));
using Mask4 = long long __attribute__((vector_size(32)));

inline Double4 load4(const double* p) {
  Double4 v;
  std::memcpy(&v, p, sizeof v);
  return v;
}

inline Double4 splat4(double x) { return Double4{x, x, x, x}; }

template <int kx, int ky, int kz, int kLanes>
inline unsigned intersectPermuted4(const WatertightLanes<kLanes>& r, int first, const glm::dvec3& v0,
                                   const glm::dvec3& v1, const glm::dvec3& v2, TriangleHit* hits) {
  const Double4 ox = load4(r.origin[kx] + first), oy = load4(r.origin[ky] + first), oz = load4(r.origin[kz] + first);
  const Double4 shearX = load4(r.shearX + first), shearY = load4(r.shearY + first), shearZ = load4(r.shearZ + first);
  const Double4 ax = splat4(v0[kx]) - ox, ay = splat4(v0[ky]) - oy, az = splat4(v0[kz]) - oz;
  const Double4 bx = splat4(v1[kx]) - ox, by = splat4(v1[ky]) - oy, bz = splat4(v1[kz]) - oz;
  const Double4 cx = splat4(v2[kx]) - ox, cy = splat4(v2[ky]) - oy, cz = splat4(v2[kz]) - oz;
  const Double4 pax = ax - shearX * az, pay = ay - shearY * az;
  const Double4 pbx = bx - shearX * bz, pby = by - shearY * bz;
  const Double4 pcx = cx - shearX * cz, pcy = cy - shearY * cz;

  // edgeFunction(pc, pb), edgeFunction(pa, pc), edgeFunction(pb, pa), as in intersectPermuted.
  const Double4 u = pcx * pby - pcy * pbx;
  const Double4 v = pax * pcy - pay * pcx;
  const Double4 w = pbx * pay - pby * pax;
  const Double4 zero{};
  const Mask4 negative = (u < zero) | (v < zero) | (w < zero);
  const Mask4 positive = (u > zero) | (v > zero) | (w > zero);
  const Double4 det = u + v + w;
  const Double4 t = (u * (shearZ * az) + v * (shearZ * bz) + w * (shearZ * cz)) / det;
  // Lanes the scalar test leaves early compute on (their quotients may be infinite or NaN) and are masked out.
  const Mask4 inside = ~(negative & positive) & (det != zero) & (t >= load4(r.tNear + first)) &
                       (t <= load4(r.tFar + first));
  const Double4 b1 = v / det;
  const Double4 b2 = w / det;
  unsigned mask = 0;
  for (int j = 0; j < kWatertightWidth; ++j) {
    if (!inside[j]) continue;
    mask |= 1u << j;
    hits[j] = TriangleHit{t[j], b1[j], b2[j]};
  }
  return mask;
}

}  // namespace watertight_detail

// Lanes first .. first + 3 of `rays` (first a multiple of kWatertightWidth), read as if each had the axis
// permutation `permutation`: bit j of the result is set when lane first + j hits the triangle within its
// [tNear, tFar], and hits[j] is then its hit. For a lane whose own permutation it is, exactly
// intersectWatertight's answer; the caller ignores the other lanes' bits.
template <int kLanes>
inline unsigned intersectWatertight4(const WatertightLanes<kLanes>& rays, int first, int permutation,
                                     const glm::dvec3& v0, const glm::dvec3& v1, const glm::dvec3& v2,
                                     TriangleHit hits[kWatertightWidth]) {
  return withWatertightAxes(permutation, [&](auto axes) {
    using A = decltype(axes);
    return watertight_detail::intersectPermuted4<A::kx, A::ky, A::kz>(rays, first, v0, v1, v2, hits);
  });
}

}  // namespace rayview
