// The reference back-end: the double-precision BVH behind the Accel interface. Independent of Embree, it is
// the accuracy yardstick and the traversal used when Embree is not installed.
#include <cmath>

#include "accel_backends.h"
#include "reference_bvh.h"

namespace rayview {
namespace {

bool isFinite(const glm::dvec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

class ReferenceAccel final : public Accel {
 public:
  ReferenceAccel(const glm::dvec3& origin, const SceneGeometry& scene, std::unique_ptr<ReferenceBvh> bvh)
      : Accel(origin, scene), bvh_(std::move(bvh)) {}

  std::optional<Hit> closestHit(const Ray& ray) const override {
    BvhRay r;
    if (!toBvhRay(ray, r)) return std::nullopt;
    BvhHit hit;
    if (!bvh_->closestHit(r, hit)) return std::nullopt;
    return Hit{hit.hit.t, hit.triangle, hit.hit.b1, hit.hit.b2};
  }

  bool occluded(const Ray& ray) const override {
    BvhRay r;
    return toBvhRay(ray, r) && bvh_->occluded(r);
  }

  AccelKind kind() const override { return AccelKind::Reference; }

 private:
  // False for a ray that cannot hit anything: zero or non-finite direction, NaN or empty interval.
  static bool toBvhRay(const Ray& ray, BvhRay& out) {
    if (!isFinite(ray.origin) || !isFinite(ray.direction)) return false;
    if (ray.direction == glm::dvec3(0.0) || !(ray.tNear <= ray.tFar)) return false;
    out = {ray.origin, ray.direction, ray.tNear, ray.tFar, ray.excludedTriangle};
    return true;
  }

  std::unique_ptr<ReferenceBvh> bvh_;
};

}  // namespace

std::unique_ptr<Accel> makeReferenceAccel(const SceneGeometry& scene, const glm::dvec3& origin, BuildProgress progress,
                                          void* progressUser, const CutOuts* cutOuts) {
  // Relative to the origin in double, once; the traversal never sees world coordinates.
  SceneArray<glm::dvec3> relative;
  relative.reserve(scene.vertices.size());
  for (const glm::dvec3& v : scene.vertices) relative.push_back(v - origin);
  std::unique_ptr<ReferenceBvh> bvh = ReferenceBvh::build(relative, scene.triangles, progress, progressUser);
  if (!bvh) return nullptr;
  bvh->setCutOuts(cutOuts);
  return std::make_unique<ReferenceAccel>(origin, scene, std::move(bvh));
}

}  // namespace rayview
