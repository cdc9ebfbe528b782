#include "rayview/scene_bounds.h"

#include <cmath>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

namespace rayview {
namespace {

bool isUsable(const glm::dvec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z) && glm::length(v) > 0.0;
}

}  // namespace

double Bounds::radius() const { return empty ? 0.0 : glm::length(max - min) * 0.5; }

void Bounds::add(const glm::dvec3& p) {
  if (empty) {
    min = max = p;
    empty = false;
    return;
  }
  min = glm::min(min, p);
  max = glm::max(max, p);
}

Bounds sceneBounds(const Scene& scene) {
  Bounds bounds;
  for (const Triangle& triangle : scene.triangles)
    for (std::uint32_t index : triangle.vertex)
      if (index < scene.vertices.size()) bounds.add(scene.vertices[index]);
  return bounds;
}

glm::dvec3 orbitPivot(const Camera& camera, const Bounds& bounds) {
  const double radius = bounds.radius() > 0.0 ? bounds.radius() : 1.0;
  const glm::dvec3 forward = isUsable(camera.gaze) ? glm::normalize(camera.gaze) : glm::dvec3(0, 0, -1);
  double along = bounds.empty ? 0.0 : glm::dot(bounds.center() - camera.position, forward);
  if (!(along > kMinimumDistanceFraction * radius)) along = radius;
  return camera.position + forward * along;
}

glm::dvec3 rotateAbout(const glm::dvec3& v, const glm::dvec3& axis, double angle) {
  const double c = std::cos(angle), s = std::sin(angle);
  return v * c + glm::cross(axis, v) * s + axis * glm::dot(axis, v) * (1.0 - c);
}

Camera turntableCamera(const Camera& camera, const glm::dvec3& pivot, int frame, int frames) {
  if (frame == 0 || frames <= 0) return camera;
  const glm::dvec3 axis = isUsable(camera.up) ? glm::normalize(camera.up) : glm::dvec3(0, 1, 0);
  const double angle = 2.0 * 3.14159265358979323846 * static_cast<double>(frame) / static_cast<double>(frames);
  Camera turned = camera;
  // Everything turns with the eye about the axis through the pivot: the view of the pivot stays as framed.
  turned.position = pivot + rotateAbout(camera.position - pivot, axis, angle);
  turned.gaze = rotateAbout(camera.gaze, axis, angle);
  turned.up = rotateAbout(camera.up, axis, angle);
  return turned;
}

}  // namespace rayview
