#pragma once
// Watertight ray/triangle intersection (Woop, Benthin and Wald, "Watertight Ray/Triangle Intersection",
// JCGT 2(1), 2013), in double precision.
//
// The ray is moved to a frame where it starts at the origin and runs along +z: translate by the ray
// origin, permute the axes so that z is the largest direction component, then shear x and y so that the
// direction becomes (0, 0, 1). In that frame the test is two-dimensional: the signs of the three edge
// functions of the projected vertices about the origin. The transformation is the same for every triangle
// a ray meets, so a vertex shared by two triangles lands on exactly the same sheared coordinates in both.
//
// Tie rule. Two triangles sharing an edge list its vertices in opposite orders, and edge(p, q) = p.x q.y -
// p.y q.x is exactly -edge(q, p): the two products are the same roundings, and rounding to nearest is
// symmetric under negation (only the sign of an exact zero can differ). So a ray through the shared edge is
// inside exactly one of them, or exactly on the edge (value zero), and zero counts as inside for both.
// Never neither. This needs each product rounded on its own: a fused multiply-add would round one product
// and not the other. The build forbids contraction (-ffp-contract=off, CMakeLists.txt), and
// WatertightEdge.IsAntisymmetricBitForBit checks it. (The vertices were once put in a canonical
// order first, which held under fusion too, but its three unpredictable branches per test cost 4-6 % of
// a render.) The paper's fallback (recompute in double when an edge function is exactly zero in float) is
// not needed: everything here is already double.

#include <cstdint>

#include <glm/vec3.hpp>

namespace rayview {

// A ray prepared for the watertight test: its origin and the permutation and shear that map it onto +z.
struct WatertightRay {
  glm::dvec3 origin{0.0};
  int kx = 0, ky = 1, kz = 2;
  double shearX = 0.0, shearY = 0.0, shearZ = 1.0;
};

// `direction` must be finite and non-zero.
inline WatertightRay prepareWatertightRay(const glm::dvec3& origin, const glm::dvec3& direction) {
  WatertightRay r;
  r.origin = origin;
  const glm::dvec3 a(direction.x < 0 ? -direction.x : direction.x, direction.y < 0 ? -direction.y : direction.y,
                     direction.z < 0 ? -direction.z : direction.z);
  r.kz = a.x > a.y ? (a.x > a.z ? 0 : 2) : (a.y > a.z ? 1 : 2);
  r.kx = (r.kz + 1) % 3;
  r.ky = (r.kx + 1) % 3;
  // Keep the winding (the sign of the edge functions) independent of the direction's sign.
  if (direction[r.kz] < 0.0) {
    const int swap = r.kx;
    r.kx = r.ky;
    r.ky = swap;
  }
  r.shearX = direction[r.kx] / direction[r.kz];
  r.shearY = direction[r.ky] / direction[r.kz];
  r.shearZ = 1.0 / direction[r.kz];
  return r;
}

struct TriangleHit {
  double t = 0.0;              // in units of |direction|
  double b1 = 0.0, b2 = 0.0;   // weights of vertex 1 and 2 (Embree's u, v)
};

namespace watertight_detail {

struct Projected {
  double x, y;
};

// Twice the signed area of (origin, p, q). edge(p, q) == -edge(q, p) bit for bit, but for the sign of zero
// (the tie rule above).
inline double edgeFunction(const Projected& p, const Projected& q) { return p.x * q.y - p.y * q.x; }

}  // namespace watertight_detail

namespace watertight_detail {

// The test with the ray's axis permutation known at compile time (kx, ky, kz as in WatertightRay): the same
// operations on the same numbers as indexing at run time, without a vertex's three differences going through
// memory to be picked by index.
template <int kx, int ky, int kz>
inline bool intersectPermuted(const WatertightRay& ray, const glm::dvec3& v0, const glm::dvec3& v1,
                              const glm::dvec3& v2, double tNear, double tFar, TriangleHit& hit) {
  const double ax = v0[kx] - ray.origin[kx], ay = v0[ky] - ray.origin[ky], az = v0[kz] - ray.origin[kz];
  const double bx = v1[kx] - ray.origin[kx], by = v1[ky] - ray.origin[ky], bz = v1[kz] - ray.origin[kz];
  const double cx = v2[kx] - ray.origin[kx], cy = v2[ky] - ray.origin[ky], cz = v2[kz] - ray.origin[kz];
  const Projected pa{ax - ray.shearX * az, ay - ray.shearY * az};
  const Projected pb{bx - ray.shearX * bz, by - ray.shearY * bz};
  const Projected pc{cx - ray.shearX * cz, cy - ray.shearY * cz};

  // u, v, w: the edge functions opposite vertex 0, 1, 2 (so, scaled, their barycentric weights).
  const double u = edgeFunction(pc, pb);
  const double v = edgeFunction(pa, pc);
  const double w = edgeFunction(pb, pa);
  // Mixed signs: outside. Without short-circuits: one branch instead of up to six unpredictable ones.
  const bool negative = (u < 0.0) | (v < 0.0) | (w < 0.0);
  const bool positive = (u > 0.0) | (v > 0.0) | (w > 0.0);
  if (negative & positive) return false;
  const double det = u + v + w;
  if (det == 0.0) return false;  // the ray lies in the triangle's plane, or the triangle is degenerate

  const double t = (u * (ray.shearZ * az) + v * (ray.shearZ * bz) + w * (ray.shearZ * cz)) / det;
  if (!(t >= tNear && t <= tFar)) return false;  // also rejects NaN
  hit.t = t;
  hit.b1 = v / det;
  hit.b2 = w / det;
  return true;
}

}  // namespace watertight_detail

// The ray's axis permutation as one number, 0 to 5: kz * 2, plus 1 when (kx, ky) is swapped. (kx, ky) is
// (kz + 1, kz + 2) mod 3, or swapped for a direction along -kz (prepareWatertightRay).
inline int watertightPermutation(const WatertightRay& ray) {
  const bool swapped = ray.kx != (ray.kz + 1) % 3;
  return ray.kz * 2 + (swapped ? 1 : 0);
}

// A permutation's axes as compile-time constants.
template <int kx_, int ky_, int kz_>
struct WatertightAxes {
  static constexpr int kx = kx_, ky = ky_, kz = kz_;
};

// f(WatertightAxes<kx, ky, kz>{}) for watertightPermutation's number: the one table of the six, for the scalar
// test and the four-lane one (watertight_lanes.h).
template <class F>
[[gnu::always_inline]] inline auto withWatertightAxes(int permutation, F&& f) {
  switch (permutation) {
    case 0: return f(WatertightAxes<1, 2, 0>{});
    case 1: return f(WatertightAxes<2, 1, 0>{});
    case 2: return f(WatertightAxes<2, 0, 1>{});
    case 3: return f(WatertightAxes<0, 2, 1>{});
    case 4: return f(WatertightAxes<0, 1, 2>{});
    default: return f(WatertightAxes<1, 0, 2>{});
  }
}

// Intersects the ray with triangle (v0, v1, v2); reports a hit with tNear <= t <= tFar. No back-face culling.
inline bool intersectWatertight(const WatertightRay& ray, const glm::dvec3& v0, const glm::dvec3& v1,
                                const glm::dvec3& v2, double tNear, double tFar, TriangleHit& hit) {
  return withWatertightAxes(watertightPermutation(ray), [&](auto axes) {
    using A = decltype(axes);
    return watertight_detail::intersectPermuted<A::kx, A::ky, A::kz>(ray, v0, v1, v2, tNear, tFar, hit);
  });
}

// The closest-hit rule both traversals share. Hits whose distances agree to kHitTieTolerance (relative)
// are a tie (coincident or duplicated faces, a shared edge), won by the lower triangle index: so which
// triangle a ray sees does not depend on traversal order, nor on the rounding that moving or scaling
// the scene changes.
inline constexpr double kHitTieTolerance = 1e-9;

// How far a search must still look once a hit at tBest is known: ties lie slightly beyond it.
inline double tieSearchLimit(double tBest) { return tBest * (1.0 + kHitTieTolerance); }

// Whether a hit (t, id) replaces the closest one so far (tBest, idBest).
inline bool replacesClosestHit(double t, std::uint32_t id, double tBest, std::uint32_t idBest) {
  if (t < tBest * (1.0 - kHitTieTolerance)) return true;
  return t <= tieSearchLimit(tBest) && id < idBest;
}

}  // namespace rayview
