#include "rayview/scene.h"

#include <algorithm>

namespace rayview {

bool SceneParameters::hasMirrors() const {
  if (maxRayDepth <= 0) return false;
  for (const Material& m : materials)
    if (m.isMirror()) return true;
  return false;
}

std::uint32_t SceneGeometry::meshOf(std::uint32_t triangle) const {
  // The last mesh starting at or before the triangle: an empty mesh never wins over the one that holds it,
  // since ranges come in order and an empty one shares its start with the next.
  const auto after = std::upper_bound(meshes.begin(), meshes.end(), triangle,
                                      [](std::uint32_t t, const Mesh& m) { return t < m.firstTriangle; });
  return after == meshes.begin() ? 0u : static_cast<std::uint32_t>(after - meshes.begin() - 1);
}

void appendFace(std::vector<Triangle>& triangles, std::vector<FaceAttributes>& faceAttributes, const Triangle& triangle,
                const FaceAttributes& attributes) {
  if (attributes.any() || !faceAttributes.empty()) {
    faceAttributes.resize(triangles.size());  // the plain faces before the first with attributes: none
    faceAttributes.push_back(attributes);
  }
  triangles.push_back(triangle);
}

void SceneGeometry::addFace(const Triangle& triangle, const FaceAttributes& attributes) {
  appendFace(triangles, faceAttributes, triangle, attributes);
}

}  // namespace rayview
