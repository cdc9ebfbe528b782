#include "rayview/accel.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <mutex>
#include <string>

#include <glm/common.hpp>

#include "accel_backends.h"
#include "rayview/build_features.h"
#ifdef RAYVIEW_HAVE_EMBREE
#include "embree_library.h"
#endif

namespace rayview {

namespace {

std::string scientific(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.3g", v);
  return buffer;
}

double largestComponent(const glm::dvec3& v) { return std::max({std::fabs(v.x), std::fabs(v.y), std::fabs(v.z)}); }

// The farthest point, relative to `origin`, that rays start at or reach, and what it is.
struct Reach {
  double distance = 0.0;
  std::string what = "the camera";
  void consider(const glm::dvec3& p, const glm::dvec3& origin, std::string_view name) {
    const double r = largestComponent(p - origin);
    if (std::isfinite(r) && r > distance) distance = r, what = name;
  }
};

// Non-finite vertices are left out: their triangles have no surface, and Embree skips invalid boxes.
// One pass over the faces' corners, nothing but the distance kept in the loop (it is the whole cost: 92 000
// triangles read 276 000 corners).
Reach geometryReach(const SceneGeometry& geometry, const glm::dvec3& origin) {
  const glm::dvec3* vertices = geometry.vertices.data();
  const std::size_t count = geometry.vertices.size();
  double farthest = 0.0;
  for (const Triangle& t : geometry.triangles)
    for (std::uint32_t v : t.vertex)
      if (v < count) {
        const double r = largestComponent(vertices[v] - origin);
        if (std::isfinite(r) && r > farthest) farthest = r;
      }
  Reach reach;
  if (farthest > 0.0) reach.distance = farthest, reach.what = "a vertex";
  return reach;
}

std::string beyond(const Reach& reach, double epsilon) {
  const double limit = kEmbreeCoordinateLimit;
  if (reach.distance * (1.0 + 0x1p-10) + epsilon <= limit) return {};
  return reach.what + " is " + scientific(reach.distance) + " from the camera" +
         (epsilon > 0.0 ? " (with <shadowrayepsilon> " + scientific(epsilon) + ")" : std::string()) +
         ", beyond the " + scientific(limit) + " Embree can represent";
}

}  // namespace

Accel::Accel(const glm::dvec3& origin, const SceneGeometry& scene) : origin_(origin) {
  // Relative to the origin as each back-end makes its corners: the same rounding.
  const auto relative = [&](const glm::dvec3& v, glm::dvec3& p) {
    p = v - origin;
    return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z);
  };
  const std::size_t triangles = scene.triangles.size();
  if (triangles > kBoxedTriangles) {
    AccelBox& box = boxes_.emplace_back();
    glm::dvec3 p;
    for (const glm::dvec3& vertex : scene.vertices)
      if (relative(vertex, p)) box.lower = glm::min(box.lower, p), box.upper = glm::max(box.upper, p);
    return;
  }
  // Where each run starts: at every mesh (up to kAccelBoxes meshes; more are grouped), the rest of the boxes
  // spread over the triangles.
  std::vector<std::size_t> starts;
  const std::size_t meshes = scene.meshes.size();
  if (meshes >= kAccelBoxes) {
    for (std::size_t g = 0; g < kAccelBoxes; ++g) starts.push_back(scene.meshes[g * meshes / kAccelBoxes].firstTriangle);
  } else {
    const std::size_t run = std::max<std::size_t>(1, (triangles + kAccelBoxes - meshes - 1) / (kAccelBoxes - meshes));
    for (const Mesh& mesh : scene.meshes)
      for (std::size_t at = mesh.firstTriangle; at < std::size_t{mesh.firstTriangle} + mesh.triangleCount; at += run)
        starts.push_back(at);
    if (meshes == 0)
      for (std::size_t at = run; at < triangles; at += run) starts.push_back(at);
  }
  // Every triangle in one run whatever the meshes say: from 0, in order, to the end.
  starts.push_back(0);
  std::sort(starts.begin(), starts.end());
  starts.erase(std::unique(starts.begin(), starts.end()), starts.end());
  starts.push_back(triangles);
  const glm::dvec3* vertices = scene.vertices.data();
  const std::size_t count = scene.vertices.size();
  for (std::size_t k = 0; k + 1 < starts.size(); ++k) {
    AccelBox box;
    for (std::size_t t = starts[k]; t < starts[k + 1] && t < triangles; ++t) {
      const Triangle& triangle = scene.triangles[t];
      glm::dvec3 corners[3];
      bool usable = true;
      for (int c = 0; c < 3; ++c)
        usable = usable && triangle.vertex[c] < count && relative(vertices[triangle.vertex[c]], corners[c]);
      if (!usable) continue;
      for (const glm::dvec3& p : corners) box.lower = glm::min(box.lower, p), box.upper = glm::max(box.upper, p);
    }
    if (!box.empty()) boxes_.push_back(box);
  }
}

std::string embreeRangeProblem(const SceneParameters& parameters, const SceneGeometry& geometry,
                               const glm::dvec3& origin) {
  // Rays start at the eye or on a surface, pushed off it by <shadowrayepsilon> (or a relative offset far
  // below 1 %); their directions are unit vectors except camera rays, which go through the near plane.
  Reach reach = geometryReach(geometry, origin);
  reach.consider(parameters.camera.position, origin, "the camera");
  parameters.lights.forEachType([&](const auto& list) {
    using Light = LightOf<decltype(list)>;
    const std::string what = "a " + std::string(Light::kType.noun);
    for (const Light& light : list)
      for (const auto& field : Light::fields())
        if (field.point) reach.consider(light.*field.point, origin, what);
  });
  const double epsilon = parameters.shadowRayEpsilon.value_or(0.0);
  const Camera& c = parameters.camera;
  const double nearPlane = c.nearDistance + std::max({std::fabs(c.left), std::fabs(c.right), std::fabs(c.bottom),
                                                      std::fabs(c.top)});
  if (!(nearPlane <= kEmbreeCoordinateLimit))
    return "the camera's near plane reaches " + scientific(nearPlane) + ", beyond the " +
           scientific(kEmbreeCoordinateLimit) + " Embree can represent";
  return beyond(reach, epsilon);
}

AccelKind accelWithinRange(const SceneGeometry& scene, AccelKind kind, const glm::dvec3& origin) {
  if (kind != AccelKind::Reference && !beyond(geometryReach(scene, origin), 0.0).empty()) return AccelKind::Reference;
  return kind;
}

std::unique_ptr<Accel> buildAccel(const SceneGeometry& scene, AccelKind kind, const glm::dvec3& origin,
                                  BuildProgress progress, void* progressUser, const CutOuts* cutOuts) {
  return buildCheckedAccel(scene, accelWithinRange(scene, kind, origin), origin, progress, progressUser, 0, cutOuts);
}

std::unique_ptr<Accel> buildCheckedAccel(const SceneGeometry& scene, AccelKind kind, const glm::dvec3& origin,
                                         BuildProgress progress, void* progressUser, std::size_t pixels,
                                         const CutOuts* cutOuts) {
  if (kind == AccelKind::Packet) return makePacketBvhAccel(scene, origin, 0, 1, cutOuts);
#ifdef RAYVIEW_HAVE_EMBREE
  if (kind == AccelKind::Embree) {
    std::string why;
    if (embreeLibrary(&why))
      return makeEmbreeAccel(scene, origin, embreeLayoutFor(scene.triangles.size(), pixels), progress, progressUser,
                             cutOuts);
    // Built with Embree, run where it cannot be loaded: the packet BVH gives the same answers, more slowly on
    // big scenes. Said once a process.
    static std::once_flag once;
    std::call_once(once, [&] {
      std::fprintf(stderr, "rayview: cannot load Embree (%s): using rayview's packet BVH instead\n", why.c_str());
    });
    return makePacketBvhAccel(scene, origin, 0, 1, cutOuts);
  }
#else
  static_cast<void>(pixels);
  // Built without Embree: the packet BVH in its place (availableAccel).
  if (kind == AccelKind::Embree) return makePacketBvhAccel(scene, origin, 0, 1, cutOuts);
#endif
  return makeReferenceAccel(scene, origin, progress, progressUser, cutOuts);
}

}  // namespace rayview
