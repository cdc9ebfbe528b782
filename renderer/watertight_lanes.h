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
#include <utility>

#include <glm/vec3.hpp>

#include "simd4.h"
#include "watertight_triangle.h"

namespace rayview {

inline constexpr int kWatertightWidth = 4;

namespace watertight_detail {

// The component of each lane's (x, y, z) named by its axis (0, 1 or 2).
inline Double4 pickAxis(Mask4 axis, Double4 x, Double4 y, Double4 z) {
  return axis == splatMask4(0) ? x : (axis == splatMask4(1) ? y : z);
}

}  // namespace watertight_detail

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

  // Lane k as the scalar test reads it: what set() was given (or prepareFour made).
  WatertightRay ray(int k) const {
    WatertightRay r;
    r.origin = glm::dvec3(origin[0][k], origin[1][k], origin[2][k]);
    r.kz = permutation[k] / 2;
    r.kx = (r.kz + 1) % 3;
    r.ky = (r.kx + 1) % 3;
    if (permutation[k] % 2 != 0) std::swap(r.kx, r.ky);
    r.shearX = shearX[k];
    r.shearY = shearY[k];
    r.shearZ = shearZ[k];
    return r;
  }

  // Lanes first .. first + 3 (first a multiple of four) from four rays at once, given by axis: lane first + j
  // gets exactly what set(first + j, prepareWatertightRay(o_j, d_j), near[j], far[j]) gives it (the same
  // choices and the same three divisions, each rounded on its own). Defined below.
  [[gnu::always_inline]] void prepareFour(int first, const Double4 (&o)[3],
                                          const Double4 (&d)[3], Double4 near,
                                          Double4 far);
};

template <int kLanes>
inline void WatertightLanes<kLanes>::prepareFour(int first, const Double4 (&o)[3],
                                          const Double4 (&d)[3], Double4 near,
                                          Double4 far) {
  using namespace watertight_detail;
  const Double4 zero{};
  Double4 a[3];
  for (int axis = 0; axis < 3; ++axis) a[axis] = d[axis] < zero ? -d[axis] : d[axis];
  // kz = a.x > a.y ? (a.x > a.z ? 0 : 2) : (a.y > a.z ? 1 : 2), then kx, ky the next two axes in turn.
  const Mask4 one = splatMask4(1), two = splatMask4(2);
  const Mask4 kz = a[0] > a[1] ? (a[0] > a[2] ? splatMask4(0) : two) : (a[1] > a[2] ? one : two);
  const Mask4 nextX = kz == two ? splatMask4(0) : kz + one;
  const Mask4 nextY = nextX == two ? splatMask4(0) : nextX + one;
  const Double4 dz = pickAxis(kz, d[0], d[1], d[2]);
  // Keep the winding independent of the direction's sign, as prepareWatertightRay does.
  const Mask4 swapped = dz < zero;
  const Mask4 kx = swapped ? nextY : nextX, ky = swapped ? nextX : nextY;
  for (int axis = 0; axis < 3; ++axis) store4(origin[axis] + first, o[axis]);
  store4(shearX + first, pickAxis(kx, d[0], d[1], d[2]) / dz);
  store4(shearY + first, pickAxis(ky, d[0], d[1], d[2]) / dz);
  store4(shearZ + first, splat4(1.0) / dz);
  store4(tNear + first, near);
  store4(tFar + first, far);
  const Mask4 number = kz * two + (swapped & one);
  for (int j = 0; j < kWatertightWidth; ++j) permutation[first + j] = static_cast<int>(number[j]);
}

// Four lanes' hits as intersectWatertight4 gives them. Not initialised: only a hit lane's are read, and zeroing
// an array of TriangleHit (a `rep stos` per block of four, in every Embree callback) was measurable.
struct TriangleHits4 {
  double t[kWatertightWidth], b1[kWatertightWidth], b2[kWatertightWidth];
  TriangleHit operator[](int j) const { return TriangleHit{t[j], b1[j], b2[j]}; }
};

namespace watertight_detail {

template <int kx, int ky, int kz, int kLanes>
inline unsigned intersectPermuted4(const WatertightLanes<kLanes>& r, int first, const glm::dvec3& v0,
                                   const glm::dvec3& v1, const glm::dvec3& v2, TriangleHits4& hits) {
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
  store4(hits.t, t);
  store4(hits.b1, b1);
  store4(hits.b2, b2);
  unsigned mask = 0;
  for (int j = 0; j < kWatertightWidth; ++j)
    if (inside[j]) mask |= 1u << j;
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
                                     TriangleHits4& hits) {
  return withWatertightAxes(permutation, [&](auto axes) {
    using A = decltype(axes);
    return watertight_detail::intersectPermuted4<A::kx, A::ky, A::kz>(rays, first, v0, v1, v2, hits);
  });
}

}  // namespace rayview
