#include "rayview/scene.h"

#include <algorithm>
#include <cstddef>
#include <string>

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

std::string wholenessProblem(const Scene& s) {
  std::uint64_t next = 0;
  for (std::uint32_t m = 0; m < s.meshes.size(); ++m) {
    const Mesh& mesh = s.meshes[m];
    if (mesh.firstTriangle != next) return "mesh " + mesh.id + " does not start where the one before it ends";
    if (mesh.material >= s.materials.size()) return "mesh " + mesh.id + " has no real material";
    next += mesh.triangleCount;
    if (next > s.triangles.size()) return "mesh " + mesh.id + " claims more triangles than there are";
    for (std::uint32_t t = mesh.firstTriangle; t < next; ++t)
      if (s.meshOf(t) != m) return "meshOf(" + std::to_string(t) + ") is not mesh " + mesh.id;
  }
  if (next != s.triangles.size()) return "the meshes do not cover the triangles";
  if (!s.faceAttributes.empty() && s.faceAttributes.size() != s.triangles.size())
    return "face attributes are not one per triangle";
  for (std::size_t i = 0; i < s.triangles.size(); ++i) {
    const FaceAttributes& a = s.attributesOf(i);
    for (int k = 0; k < 3; ++k) {
      if (s.triangles[i].vertex[k] >= s.vertices.size()) return "triangle " + std::to_string(i) + ": a vertex out of range";
      if (a.hasTexCoords() && static_cast<std::size_t>(a.texCoord[k]) >= s.texCoords.size())
        return "triangle " + std::to_string(i) + ": a texture coordinate out of range";
      if (a.hasNormals() && static_cast<std::size_t>(a.normal[k]) >= s.normals.size())
        return "triangle " + std::to_string(i) + ": a normal out of range";
    }
  }
  return "";
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
