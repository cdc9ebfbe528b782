#include "support/coincident_faces.h"

#include <algorithm>
#include <array>
#include <map>

#include <glm/geometric.hpp>

#include "rayview/accel.h"
#include "rayview/camera_rays.h"

namespace rayview::testing {
namespace {

std::vector<bool> duplicatedFaces(const Scene& scene) {
  std::map<std::array<std::uint32_t, 3>, std::vector<std::size_t>> byVertices;
  for (std::size_t i = 0; i < scene.triangles.size(); ++i) {
    const Triangle& t = scene.triangles[i];
    std::array<std::uint32_t, 3> key{t.vertex[0], t.vertex[1], t.vertex[2]};
    std::sort(key.begin(), key.end());
    byVertices[key].push_back(i);
  }
  std::vector<bool> duplicated(scene.triangles.size(), false);
  for (const auto& [key, faces] : byVertices)
    if (faces.size() > 1)
      for (std::size_t f : faces) duplicated[f] = true;
  return duplicated;
}

}  // namespace

std::size_t countDuplicatedFaces(const Scene& scene) {
  const std::vector<bool> d = duplicatedFaces(scene);
  return static_cast<std::size_t>(std::count(d.begin(), d.end(), true));
}

std::vector<bool> coincidentFacePixels(const Scene& scene) {
  const Camera& camera = scene.camera;
  std::vector<bool> mask(static_cast<std::size_t>(camera.width) * camera.height, false);
  const std::vector<bool> duplicated = duplicatedFaces(scene);
  if (std::find(duplicated.begin(), duplicated.end(), true) == duplicated.end()) return mask;
  const std::unique_ptr<Accel> accel = buildAccel(scene, AccelKind::Reference, camera.position);
  const CameraBasis basis = cameraBasis(camera);
  for (int j = 0; j < camera.height; ++j)
    for (int i = 0; i < camera.width; ++i) {
      Ray ray{glm::vec3(0.0f), glm::vec3(glm::normalize(pixelDirection(camera, basis, i, j))), 0.0f, INFINITY};
      for (int depth = 0; depth <= scene.maxRayDepth; ++depth) {
        const std::optional<Hit> hit = accel->closestHit(ray);
        if (!hit) break;
        if (duplicated[hit->triangle]) {
          mask[static_cast<std::size_t>(j) * camera.width + i] = true;
          break;
        }
        const Triangle& t = scene.triangles[hit->triangle];
        if (!scene.materials[t.material].isMirror()) break;
        const glm::dvec3 a = scene.vertices[t.vertex[0]] - accel->origin();
        const glm::dvec3 b = scene.vertices[t.vertex[1]] - accel->origin();
        const glm::dvec3 c = scene.vertices[t.vertex[2]] - accel->origin();
        const glm::dvec3 n = glm::normalize(glm::cross(b - a, c - a));
        const glm::dvec3 d = glm::normalize(glm::dvec3(ray.direction));
        const glm::dvec3 p = (1.0 - hit->b1 - hit->b2) * a + double(hit->b1) * b + double(hit->b2) * c;
        ray = Ray{glm::vec3(p), glm::vec3(d - 2.0 * glm::dot(d, n) * n), 0.0f, INFINITY, hit->triangle};
      }
    }
  return mask;
}

void copyMaskedPixels(Image& actual, const Image& expected, const std::vector<bool>& mask) {
  if (actual.width != expected.width || actual.height != expected.height) return;
  for (std::size_t p = 0; p < mask.size() && 3 * p + 2 < actual.rgb.size(); ++p)
    if (mask[p])
      for (int k = 0; k < 3; ++k) actual.rgb[3 * p + k] = expected.rgb[3 * p + k];
}

}  // namespace rayview::testing
