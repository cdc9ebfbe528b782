// The reference BVH traversal: iterative, nearer child first, far child on a fixed stack.
#include "reference_bvh.h"

#include <cfloat>
#include <limits>

namespace rayview {
namespace {

// gamma(n) = n u / (1 - n u), u = 2^-53: the relative error bound of n rounded double operations.
constexpr double gamma(int n) { return n * (DBL_EPSILON / 2) / (1 - n * (DBL_EPSILON / 2)); }
// Ize 2013: each slab distance (bound - origin) * (1 / direction) carries at most gamma(3) relative error;
// widening the slab interval by 2 gamma(3) makes the box test conservative: a ray that meets the box in
// exact arithmetic is never culled by rounding.
constexpr double kSlabWidening = 2 * gamma(3);

struct BoxRay {
  glm::dvec3 origin;
  glm::dvec3 inverse;  // 1 / direction; a zero component gives +inf (never -inf, see intersectBox)
};

BoxRay prepareBoxRay(const BvhRay& ray) {
  BoxRay r{ray.origin, {}};
  for (int a = 0; a < 3; ++a)
    r.inverse[a] = ray.direction[a] == 0.0 ? std::numeric_limits<double>::infinity() : 1.0 / ray.direction[a];
  return r;
}

// The parametric interval where the ray is inside the (closed) box, clipped to [tNear, tFar]. For a
// direction component of zero the slab distances are +-inf, or NaN when the origin lies exactly on the slab
// plane; NaN compares false below, so it leaves the interval unchanged, which is right for a ray running
// inside the boundary plane.
inline bool intersectBox(const ReferenceBvh::Node& node, const BoxRay& r, double tNear, double tFar, double& tEntry) {
  for (int a = 0; a < 3; ++a) {
    double t0 = (node.lower[a] - r.origin[a]) * r.inverse[a];
    double t1 = (node.upper[a] - r.origin[a]) * r.inverse[a];
    if (t0 > t1) {
      const double swap = t0;
      t0 = t1;
      t1 = swap;
    }
    t0 *= t0 > 0.0 ? 1.0 - kSlabWidening : 1.0 + kSlabWidening;
    t1 *= t1 > 0.0 ? 1.0 + kSlabWidening : 1.0 - kSlabWidening;
    if (t0 > tNear) tNear = t0;
    if (t1 < tFar) tFar = t1;
  }
  tEntry = tNear;
  return tNear <= tFar;
}

}  // namespace

template <bool kAnyHit>
bool ReferenceBvh::traverse(const BvhRay& ray, BvhHit* out) const {
  if (nodes_.empty()) return false;
  const WatertightRay triangleRay = prepareWatertightRay(ray.origin, ray.direction);
  const BoxRay boxRay = prepareBoxRay(ray);
  double tFar = ray.tFar;  // shrinks to the closest hit so far (plus the tie band, see watertight_triangle.h)
  bool found = false;

  struct Entry {
    std::uint32_t node;
    double tEntry;
  };
  Entry stack[kMaxDepth + 1];
  int size = 0;

  double tRoot = 0.0;
  if (!intersectBox(nodes_[0], boxRay, ray.tNear, tFar, tRoot)) return false;
  std::uint32_t current = 0;
  for (;;) {
    const Node& node = nodes_[current];
    if (node.count == 0) {
      double tLeft = 0.0, tRight = 0.0;
      const bool hitLeft = intersectBox(nodes_[node.first], boxRay, ray.tNear, tFar, tLeft);
      const bool hitRight = intersectBox(nodes_[node.first + 1], boxRay, ray.tNear, tFar, tRight);
      if (hitLeft && hitRight) {
        const bool leftFirst = tLeft <= tRight;
        stack[size++] = leftFirst ? Entry{node.first + 1, tRight} : Entry{node.first, tLeft};
        current = leftFirst ? node.first : node.first + 1;
        continue;
      }
      if (hitLeft || hitRight) {
        current = hitLeft ? node.first : node.first + 1;
        continue;
      }
    } else {
      for (std::uint32_t i = node.first; i < node.first + node.count; ++i) {
        const LeafTriangle& tri = triangles_[i];
        if (tri.id == ray.excludedTriangle) continue;
        TriangleHit hit;
        if (!intersectWatertight(triangleRay, tri.v0, tri.v1, tri.v2, ray.tNear, tFar, hit)) continue;
        if (cutOuts_ && cutOuts_->hides(tri.id, hit.b1, hit.b2)) continue;
        if constexpr (kAnyHit) {
          return true;
        } else {
          if (found && !replacesClosestHit(hit.t, tri.id, out->hit.t, out->triangle)) continue;
          found = true;
          out->hit = hit;
          out->triangle = tri.id;
          tFar = std::min(ray.tFar, tieSearchLimit(hit.t));
        }
      }
    }
    // Next: the nearest postponed subtree that can still hold something closer.
    for (;;) {
      if (size == 0) return found;
      const Entry entry = stack[--size];
      if (entry.tEntry <= tFar) {
        current = entry.node;
        break;
      }
    }
  }
}

bool ReferenceBvh::closestHit(const BvhRay& ray, BvhHit& out) const { return traverse<false>(ray, &out); }

bool ReferenceBvh::occluded(const BvhRay& ray) const { return traverse<true>(ray, nullptr); }

}  // namespace rayview
