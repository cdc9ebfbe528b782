#include "support/coincident_faces.h"

#include <algorithm>
#include <array>
#include <cmath>
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
      Ray ray{glm::dvec3(0.0), glm::normalize(pixelDirection(camera, basis, i, j)), 0.0, INFINITY};
      for (int depth = 0; depth <= scene.maxRayDepth; ++depth) {
        const std::optional<Hit> hit = accel->closestHit(ray);
        if (!hit) break;
        if (duplicated[hit->triangle]) {
          mask[static_cast<std::size_t>(j) * camera.width + i] = true;
          break;
        }
        const Triangle& t = scene.triangles[hit->triangle];
        if (!scene.materials[scene.materialOf(hit->triangle)].isMirror()) break;
        const glm::dvec3 a = scene.vertices[t.vertex[0]] - accel->origin();
        const glm::dvec3 b = scene.vertices[t.vertex[1]] - accel->origin();
        const glm::dvec3 c = scene.vertices[t.vertex[2]] - accel->origin();
        const glm::dvec3 n = glm::normalize(glm::cross(b - a, c - a));
        const glm::dvec3 d = glm::normalize(ray.direction);
        const glm::dvec3 p = (1.0 - hit->b1 - hit->b2) * a + hit->b1 * b + hit->b2 * c;
        ray = Ray{p, d - 2.0 * glm::dot(d, n) * n, 0.0, INFINITY, hit->triangle};
      }
    }
  return mask;
}

std::vector<bool> boundaryEdgePixels(const Scene& scene) {
  const Camera& camera = scene.camera;
  std::vector<bool> mask(static_cast<std::size_t>(camera.width) * camera.height, false);
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> edgeUse;
  for (const Triangle& t : scene.triangles)
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t a = t.vertex[k], b = t.vertex[(k + 1) % 3];
      ++edgeUse[{std::min(a, b), std::max(a, b)}];
    }
  std::vector<std::pair<glm::dvec3, glm::dvec3>> boundary;  // relative to the camera
  for (const auto& [edge, uses] : edgeUse)
    if (uses == 1) boundary.emplace_back(scene.vertices[edge.first] - camera.position, scene.vertices[edge.second] - camera.position);
  const CameraBasis basis = cameraBasis(camera);
  for (int j = 0; j < camera.height; ++j)
    for (int i = 0; i < camera.width; ++i) {
      const glm::dvec3 d = glm::normalize(pixelDirection(camera, basis, i, j));
      for (const auto& [a, b] : boundary) {
        // The ray passes through the edge's line where the triple product of (a, b, d) vanishes.
        const glm::dvec3 e = b - a;
        const double volume = glm::dot(glm::cross(a, e), d);
        const double scale = glm::length(glm::cross(a, e)) + glm::length(glm::cross(e, d)) * glm::length(a);
        if (!(std::fabs(volume) <= 1e-9 * scale)) continue;
        // ... and within the segment, in front of the eye: the point of the edge closest to the ray.
        const glm::dvec3 n = glm::cross(d, glm::cross(e, d));
        const double denominator = glm::dot(e, n);
        if (denominator == 0.0) continue;
        const double s = -glm::dot(a, n) / denominator;
        if (s < -1e-9 || s > 1.0 + 1e-9 || glm::dot(a + s * e, d) <= 0.0) continue;
        mask[static_cast<std::size_t>(j) * camera.width + i] = true;
        break;
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
