#pragma once
// Meshes built in code for the robustness tests: a flat tessellated plane and two closed meshes (cube,
// icosphere), welded (neighbouring triangles share vertex indices), counter-clockwise seen from outside.

#include <array>
#include <cstdint>
#include <vector>

#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>

#include "rayview/scene.h"

namespace rayview::testing {

// Where a unit mesh goes: p -> centre + size * rotation * p.
struct Placement {
  glm::dvec3 centre{0.0};
  glm::dmat3 rotation{1.0};
  double size = 1.0;

  glm::dvec3 apply(const glm::dvec3& p) const { return centre + size * (rotation * p); }
};

// Rotation by `radians` about `axis` (normalised here).
glm::dmat3 rotationAbout(const glm::dvec3& axis, double radians);

// A fixed rotation that leaves no face or edge axis-aligned, so float rounding of the vertices is generic.
glm::dmat3 genericRotation();

// Each appends one Mesh to `scene` (its triangles and vertices) with material `material`.
// Flat: n x n quads over [-1,1]^2 in the plane z = 0, split along alternating diagonals, facing +z.
void addTessellatedPlane(Scene& scene, const Placement& placement, int n, std::uint32_t material);
// Closed: the surface of the cube [-1,1]^3 with n x n quads per face.
void addTessellatedCube(Scene& scene, const Placement& placement, int n, std::uint32_t material);
// Closed: an icosahedron subdivided `levels` times (4^levels * 20 triangles) on the unit sphere.
void addIcosphere(Scene& scene, const Placement& placement, int levels, std::uint32_t material);

// The edges and vertices of a mesh, with the triangles around each.
struct MeshTopology {
  struct Edge {
    std::uint32_t a, b;                    // vertex indices, a < b
    std::vector<std::uint32_t> triangles;  // 2 for an interior edge, 1 on the boundary
  };
  std::vector<Edge> edges;
  std::vector<std::vector<std::uint32_t>> vertexTriangles;  // by vertex index (empty for unused vertices)
  std::vector<bool> onBoundary;                             // by vertex index
};

MeshTopology meshTopology(const Scene& scene, const Mesh& mesh);

}  // namespace rayview::testing
