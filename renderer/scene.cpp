#include "rayview/scene.h"

#include <algorithm>
#include <cstddef>

namespace rayview {

bool SceneParameters::hasMirrors() const {
  if (maxRayDepth <= 0) return false;
  for (const Material& m : materials)
    if (m.isMirror()) return true;
  return false;
}

std::uint32_t SceneGeometry::meshOf(std::uint32_t triangle) const {
  return static_cast<std::uint32_t>(
      lastRangeAtOrBefore(meshes.size(), triangle, [&](std::size_t k) { return meshes[k].firstTriangle; }));
}

void appendFace(std::vector<Triangle>& triangles, std::vector<FaceAttributes>& faceAttributes, const Triangle& triangle,
                const FaceAttributes& attributes) {
  if (attributes.any() || !faceAttributes.empty()) {
    // Room for as many as the triangles have (the loader reserves those from the text's size): no reallocation.
    if (faceAttributes.empty()) faceAttributes.reserve(std::max(triangles.capacity(), triangles.size() + 1));
    faceAttributes.resize(triangles.size());  // the plain faces before the first with attributes: none
    faceAttributes.push_back(attributes);
  }
  triangles.push_back(triangle);
}

void SceneGeometry::addFace(const Triangle& triangle, const FaceAttributes& attributes) {
  appendFace(triangles, faceAttributes, triangle, attributes);
}

}  // namespace rayview
