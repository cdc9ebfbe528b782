#include "scene_pick.h"

#include <limits>

#include <glm/geometric.hpp>

#include "rayview/accel.h"
#include "rayview/camera_rays.h"

namespace rayview {

std::optional<PickResult> pickPixel(const Camera& camera, const PreparedGeometry& geometry, int i, int j) {
  if (i < 0 || j < 0 || i >= camera.width || j >= camera.height || !geometry.accel || !geometry.source) return std::nullopt;
  if (!cameraProblem(camera).empty()) return std::nullopt;
  const glm::dvec3 direction = glm::normalize(pixelDirection(camera, cameraBasis(camera), i, j));
  const Ray ray{camera.position - geometry.accel->origin(), direction, 0.0, std::numeric_limits<double>::infinity()};
  const std::optional<Hit> hit = geometry.accel->closestHit(ray);
  if (!hit || hit->triangle >= geometry.source->triangles.size()) return std::nullopt;
  PickResult pick;
  pick.triangle = hit->triangle;
  pick.mesh = geometry.source->meshOf(hit->triangle);
  pick.material = geometry.source->materialOf(hit->triangle);
  pick.point = camera.position + direction * hit->t;
  return pick;
}

std::string describePick(const PickResult& pick, const SceneGeometry& geometry, const SceneParameters& parameters) {
  const std::string mesh = pick.mesh < geometry.meshes.size() ? geometry.meshes[pick.mesh].id : "?";
  const std::string material = pick.material < parameters.materials.size() ? parameters.materials[pick.material].id : "?";
  return "picked mesh=" + mesh + " material=" + material + " triangle=" + std::to_string(pick.triangle);
}

}  // namespace rayview
