// Placeholder reference traversal (brute force, double precision); replaced by the reference BVH.
#include "accel_backends.h"

#include <array>
#include <vector>

#include <glm/geometric.hpp>

namespace rayview {
namespace {

class BruteForceAccel final : public Accel {
 public:
  BruteForceAccel(const Scene& scene, const glm::dvec3& origin) : Accel(origin) {
    for (const glm::dvec3& v : scene.vertices) vertices_.push_back(v - origin);
    for (const Triangle& t : scene.triangles) triangles_.push_back({t.vertex[0], t.vertex[1], t.vertex[2]});
  }
  std::optional<Hit> closestHit(const Ray& ray) const override { return trace(ray, false); }
  bool occluded(const Ray& ray) const override { return trace(ray, true).has_value(); }
  AccelKind kind() const override { return AccelKind::Reference; }

 private:
  std::optional<Hit> trace(const Ray& ray, bool any) const {
    std::optional<Hit> best;
    double tBest = ray.tFar;
    const glm::dvec3 o(ray.origin), d(ray.direction);
    for (std::size_t i = 0; i < triangles_.size(); ++i) {
      if (i == ray.excludedTriangle) continue;
      const glm::dvec3& a = vertices_[triangles_[i][0]];
      const glm::dvec3 e1 = vertices_[triangles_[i][1]] - a, e2 = vertices_[triangles_[i][2]] - a;
      const glm::dvec3 p = glm::cross(d, e2);
      const double det = glm::dot(e1, p);
      if (det == 0.0) continue;
      const glm::dvec3 s = o - a;
      const double b1 = glm::dot(s, p) / det;
      const glm::dvec3 q = glm::cross(s, e1);
      const double b2 = glm::dot(d, q) / det;
      const double t = glm::dot(e2, q) / det;
      if (b1 < 0 || b2 < 0 || b1 + b2 > 1 || t < ray.tNear || t > tBest) continue;
      tBest = t;
      best = Hit{static_cast<float>(t), static_cast<std::uint32_t>(i), static_cast<float>(b1), static_cast<float>(b2)};
      if (any) break;
    }
    return best;
  }
  std::vector<glm::dvec3> vertices_;
  std::vector<std::array<std::uint32_t, 3>> triangles_;
};

}  // namespace

std::unique_ptr<Accel> makeReferenceAccel(const Scene& scene, const glm::dvec3& origin, BuildProgress,
                                          void*) {
  return std::make_unique<BruteForceAccel>(scene, origin);
}

}  // namespace rayview
