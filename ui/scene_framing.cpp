#include "scene_framing.h"

#include <algorithm>

namespace rayview {
namespace {

double largestExtent(const Bounds& b) {
  const glm::dvec3 e = b.max - b.min;
  return std::max({e.x, e.y, e.z});
}

double smallestExtent(const Bounds& b) {
  const glm::dvec3 e = b.max - b.min;
  return std::min({e.x, e.y, e.z});
}

Bounds merged(Bounds a, const Bounds& b) {
  if (!b.empty) {
    a.add(b.min);
    a.add(b.max);
  }
  return a;
}

}  // namespace

std::vector<Bounds> meshBounds(const SceneGeometry& geometry) {
  std::vector<Bounds> bounds(geometry.meshes.size());
  for (std::size_t m = 0; m < geometry.meshes.size(); ++m) {
    const Mesh& mesh = geometry.meshes[m];
    const std::size_t end = geometry.meshEnd(mesh);
    for (std::size_t t = mesh.firstTriangle; t < end; ++t)
      for (const std::uint32_t index : geometry.triangles[t].vertex)
        if (index < geometry.vertices.size()) bounds[m].add(geometry.vertices[index]);
  }
  return bounds;
}

bool isGroundPlane(const Bounds& mesh, const Bounds& rest) {
  if (mesh.empty || rest.empty) return false;  // the only mesh is the subject, however flat
  const double largest = largestExtent(mesh);
  return largest > 0.0 && smallestExtent(mesh) < kGroundFlatness * largest &&
         largest > kGroundDominance * largestExtent(rest);
}

Bounds framingBounds(const SceneGeometry& geometry, std::optional<std::size_t> selectedMesh) {
  const std::vector<Bounds> meshes = meshBounds(geometry);
  if (selectedMesh && *selectedMesh < meshes.size() && !meshes[*selectedMesh].empty) return meshes[*selectedMesh];
  // The union of all meshes but one, for each: prefix and suffix unions.
  const std::size_t n = meshes.size();
  std::vector<Bounds> before(n + 1), after(n + 1);
  for (std::size_t i = 0; i < n; ++i) before[i + 1] = merged(before[i], meshes[i]);
  for (std::size_t i = n; i-- > 0;) after[i] = merged(after[i + 1], meshes[i]);
  Bounds subject;
  for (std::size_t i = 0; i < n; ++i)
    if (!isGroundPlane(meshes[i], merged(before[i], after[i + 1]))) subject = merged(subject, meshes[i]);
  return subject.empty ? before[n] : subject;
}

}  // namespace rayview
