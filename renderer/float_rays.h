#pragma once
// Private: the float rays the fast back-ends traverse with, made from the double rays of a query. The Embree back-end
// hands them to Embree; rayview's packet BVH tests its float boxes with them. Both take exactly the same rays, which
// is half of why they answer alike (the other half: the same boxes, the same watertight test and tie rule).

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <optional>
#include <vector>

#include <glm/common.hpp>

#include "float_steps.h"
#include "rayview/accel.h"
#include "rayview/cut_outs.h"
#include "simd4.h"
#include "watertight_lanes.h"
#include "watertight_triangle.h"

namespace rayview {

// A triangle's corners relative to the accel's origin, in double: what both fast back-ends test and bound.
struct TriangleCorners {
  glm::dvec3 a, b, c;
};

inline TriangleCorners cornersOf(const SceneArray<glm::dvec3>& vertices, const Triangle& triangle,
                                 const glm::dvec3& origin) {
  const auto& v = triangle.vertex;
  return {vertices[v[0]] - origin, vertices[v[1]] - origin, vertices[v[2]] - origin};
}

// The float box both fast back-ends bound a triangle with, so that they meet the same triangles: the corners
// rounded to float, widened by 2^-20 of the largest coordinate (the rounding may cut a vertex off, and Embree's
// traversal of user geometry is not conservative at box corners).
struct FloatBox {
  glm::vec3 lower, upper;
};

inline FloatBox floatBoxOf(const TriangleCorners& t) {
  FloatBox box{glm::vec3(INFINITY), glm::vec3(-INFINITY)};
  for (const glm::dvec3* corner : {&t.a, &t.b, &t.c}) {
    box.lower = glm::min(box.lower, glm::vec3(*corner));
    box.upper = glm::max(box.upper, glm::vec3(*corner));
  }
  const float margin = 0x1p-20f * std::max({std::fabs(box.lower.x), std::fabs(box.lower.y), std::fabs(box.lower.z),
                                           std::fabs(box.upper.x), std::fabs(box.upper.y), std::fabs(box.upper.z)});
  box.lower -= margin;
  box.upper += margin;
  return box;
}

// Whether a ray goes to the float traversal: within kEmbreeCoordinateLimit, an interval starting at or after 0 and
// ending somewhere. The others are answered by testing every triangle in double.
inline bool floatTraversable(const Ray& ray) {
  const double limit = kEmbreeCoordinateLimit;
  for (int k = 0; k < 3; ++k)
    if (!(std::fabs(ray.origin[k]) <= limit) || !(std::fabs(ray.direction[k]) <= limit)) return false;
  return ray.tNear >= 0.0 && !std::isnan(ray.tFar);
}

// A float ray: origin and direction rounded to nearest, the interval widened outwards (widenedNear, widenedFar:
// never below 0).
struct FloatRay {
  float origin[3], direction[3], tNear, tFar;
};

inline FloatRay floatRay(const Ray& ray) {
  FloatRay f;
  for (int k = 0; k < 3; ++k) {
    f.origin[k] = static_cast<float>(ray.origin[k]);
    f.direction[k] = static_cast<float>(ray.direction[k]);
  }
  f.tNear = widenedNear(ray.tNear);
  f.tFar = widenedFar(ray.tFar);
  return f;
}

// Four rays of a query at once, lanes first .. first + 3 (lanes from `count` on read an empty ray): `packed` gets
// their watertight lanes, and the result their float rays (floatRay's, lane for lane) and which of them
// floatTraversable takes (`usable`; the others' float fields are zero).
struct FloatRays4 {
  Float4 origin[3], direction[3], tNear, tFar;
  Int4 usable, inCount;
};

template <int kLanes>
[[gnu::always_inline]] inline FloatRays4 prepareFourRays(const Ray* rays, int first, int count,
                                                         WatertightLanes<kLanes>& packed) {
  // Built in registers from four rays: vectors assembled in memory element by element stall every load of them
  // (no store forwarding from four stores to one load).
  static const Ray kNone{};
  const Ray* r[kWatertightWidth];
  for (int j = 0; j < kWatertightWidth; ++j) r[j] = first + j < count ? &rays[first + j] : &kNone;
  auto gather = [&](auto field) { return Double4{field(*r[0]), field(*r[1]), field(*r[2]), field(*r[3])}; };
  Double4 o[3], d[3];
  for (int axis = 0; axis < 3; ++axis) {
    o[axis] = gather([axis](const Ray& ray) { return ray.origin[axis]; });
    d[axis] = gather([axis](const Ray& ray) { return ray.direction[axis]; });
  }
  const Double4 near = gather([](const Ray& ray) { return ray.tNear; });
  const Double4 far = gather([](const Ray& ray) { return ray.tFar; });
  FloatRays4 f;
  f.inCount = Int4{first, first + 1, first + 2, first + 3} < count;
  packed.prepareFour(first, o, d, near, far);
  // floatTraversable(), lane by lane.
  const Double4 limit = splat4(kEmbreeCoordinateLimit);
  Mask4 wide = (near >= Double4{}) & (far == far);
  for (int axis = 0; axis < 3; ++axis) wide &= (abs4(o[axis]) <= limit) & (abs4(d[axis]) <= limit);
  f.usable = __builtin_convertvector(wide, Int4) & f.inCount;
  // floatRay(), lane by lane.
  auto toFloat = [&](Double4 v) { return f.usable ? __builtin_convertvector(v, Float4) : Float4{}; };
  const Float4 zero{};
  f.tNear = widenedNear4(toFloat(near));
  f.tFar = f.usable ? widenedFar4(__builtin_convertvector(far, Float4)) : zero;
  for (int axis = 0; axis < 3; ++axis) {
    f.origin[axis] = toFloat(o[axis]);
    f.direction[axis] = toFloat(d[axis]);
  }
  return f;
}

// A ray floatTraversable turns away, answered by testing every triangle in double: `corners(i)` gives triangle i's
// corners relative to the accel's origin (members a, b, c), for i < count; a hit `cutOuts` hides (null for none)
// does not count.
template <class Corners>
std::optional<Hit> closestHitByEveryTriangle(const Ray& ray, std::uint32_t count, const CutOuts* cutOuts,
                                             Corners&& corners) {
  const WatertightRay prepared = prepareWatertightRay(ray.origin, ray.direction);
  std::optional<Hit> best;
  for (std::uint32_t i = 0; i < count; ++i) {
    if (i == ray.excludedTriangle) continue;
    const auto t = corners(i);
    TriangleHit hit;
    const double tFar = best ? std::min(ray.tFar, tieSearchLimit(best->t)) : ray.tFar;
    if (!intersectWatertight(prepared, t.a, t.b, t.c, ray.tNear, tFar, hit)) continue;
    if (cutOuts && cutOuts->hides(i, hit.b1, hit.b2)) continue;
    if (best && !replacesClosestHit(hit.t, i, best->t, best->triangle)) continue;
    best = Hit{hit.t, i, hit.b1, hit.b2};
  }
  return best;
}

template <class Corners>
bool occludedByAnyTriangle(const Ray& ray, std::uint32_t count, const CutOuts* cutOuts, Corners&& corners) {
  const WatertightRay prepared = prepareWatertightRay(ray.origin, ray.direction);
  for (std::uint32_t i = 0; i < count; ++i) {
    if (i == ray.excludedTriangle) continue;
    const auto t = corners(i);
    TriangleHit hit;
    if (intersectWatertight(prepared, t.a, t.b, t.c, ray.tNear, ray.tFar, hit) &&
        !(cutOuts && cutOuts->hides(i, hit.b1, hit.b2)))
      return true;
  }
  return false;
}

}  // namespace rayview
