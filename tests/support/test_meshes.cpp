#include "support/test_meshes.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <string>
#include <utility>

#include <glm/geometric.hpp>

namespace rayview::testing {
namespace {

// Appends the Mesh record for triangles added since `firstTriangle`.
void closeMesh(Scene& scene, std::uint32_t firstTriangle, std::uint32_t material, const char* name) {
  const auto meshIndex = static_cast<std::uint32_t>(scene.meshes.size());
  const auto count = static_cast<std::uint32_t>(scene.triangles.size()) - firstTriangle;
  scene.meshes.push_back(Mesh{std::string(name) + std::to_string(meshIndex), material, firstTriangle, count});
}

void addFace(Scene& scene, std::uint32_t a, std::uint32_t b, std::uint32_t c) {
  Triangle t;
  t.vertex[0] = a;
  t.vertex[1] = b;
  t.vertex[2] = c;
  scene.triangles.push_back(t);
}

}  // namespace

glm::dmat3 rotationAbout(const glm::dvec3& axis, double radians) {
  const glm::dvec3 k = glm::normalize(axis);
  const double c = std::cos(radians), s = std::sin(radians), t = 1.0 - c;
  // Rodrigues' formula; glm matrices are column-major: m[column][row].
  glm::dmat3 m;
  m[0] = {t * k.x * k.x + c, t * k.x * k.y + s * k.z, t * k.x * k.z - s * k.y};
  m[1] = {t * k.x * k.y - s * k.z, t * k.y * k.y + c, t * k.y * k.z + s * k.x};
  m[2] = {t * k.x * k.z + s * k.y, t * k.y * k.z - s * k.x, t * k.z * k.z + c};
  return m;
}

glm::dmat3 genericRotation() { return rotationAbout({0.3, -0.8, 0.52}, 0.7371); }

void addTessellatedPlane(Scene& scene, const Placement& placement, int n, std::uint32_t material) {
  const auto first = static_cast<std::uint32_t>(scene.vertices.size());
  const auto firstTriangle = static_cast<std::uint32_t>(scene.triangles.size());
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) scene.vertices.push_back(placement.apply({-1.0 + 2.0 * i / n, -1.0 + 2.0 * j / n, 0.0}));
  auto at = [&](int i, int j) { return first + static_cast<std::uint32_t>(j * (n + 1) + i); };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const std::uint32_t a = at(i, j), b = at(i + 1, j), c = at(i + 1, j + 1), d = at(i, j + 1);
      if ((i + j) % 2 == 0) {
        addFace(scene, a, b, c);
        addFace(scene, a, c, d);
      } else {
        addFace(scene, a, b, d);
        addFace(scene, b, c, d);
      }
    }
  closeMesh(scene, firstTriangle, material, "plane");
}

void addTessellatedCube(Scene& scene, const Placement& placement, int n, std::uint32_t material) {
  const auto firstTriangle = static_cast<std::uint32_t>(scene.triangles.size());
  // Vertices keyed by their lattice coordinates, so the six faces share their border vertices.
  std::map<std::array<int, 3>, std::uint32_t> lattice;
  auto vertex = [&](std::array<int, 3> p) {
    auto [it, inserted] = lattice.try_emplace(p, static_cast<std::uint32_t>(scene.vertices.size()));
    if (inserted) scene.vertices.push_back(placement.apply({-1.0 + 2.0 * p[0] / n, -1.0 + 2.0 * p[1] / n, -1.0 + 2.0 * p[2] / n}));
    return it->second;
  };
  for (int axis = 0; axis < 3; ++axis)
    for (int side = 0; side < 2; ++side) {
      const int u = (axis + 1) % 3, v = (axis + 2) % 3;  // (u, v, axis) is right-handed
      for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
          auto corner = [&](int di, int dj) {
            std::array<int, 3> p{};
            p[axis] = side * n;
            p[u] = i + di;
            p[v] = j + dj;
            return vertex(p);
          };
          const std::uint32_t a = corner(0, 0), b = corner(1, 0), c = corner(1, 1), d = corner(0, 1);
          if (side == 1) {  // normal +axis: counter-clockwise in (u, v)
            addFace(scene, a, b, c);
            addFace(scene, a, c, d);
          } else {
            addFace(scene, a, c, b);
            addFace(scene, a, d, c);
          }
        }
    }
  closeMesh(scene, firstTriangle, material, "cube");
}

void addIcosphere(Scene& scene, const Placement& placement, int levels, std::uint32_t material) {
  const double g = (1.0 + std::sqrt(5.0)) / 2.0;
  std::vector<glm::dvec3> points = {{-1, g, 0}, {1, g, 0}, {-1, -g, 0}, {1, -g, 0}, {0, -1, g}, {0, 1, g},
                                    {0, -1, -g}, {0, 1, -g}, {g, 0, -1}, {g, 0, 1}, {-g, 0, -1}, {-g, 0, 1}};
  for (glm::dvec3& p : points) p = glm::normalize(p);
  std::vector<std::array<std::uint32_t, 3>> faces = {
      {0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
      {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},   {4, 9, 5}, {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
  for (int level = 0; level < levels; ++level) {
    std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> midpoints;
    auto midpoint = [&](std::uint32_t a, std::uint32_t b) {
      auto [it, inserted] = midpoints.try_emplace({std::min(a, b), std::max(a, b)}, static_cast<std::uint32_t>(points.size()));
      if (inserted) points.push_back(glm::normalize(points[a] + points[b]));
      return it->second;
    };
    std::vector<std::array<std::uint32_t, 3>> finer;
    for (const auto& f : faces) {
      const std::uint32_t ab = midpoint(f[0], f[1]), bc = midpoint(f[1], f[2]), ca = midpoint(f[2], f[0]);
      finer.insert(finer.end(), {{f[0], ab, ca}, {f[1], bc, ab}, {f[2], ca, bc}, {ab, bc, ca}});
    }
    faces = std::move(finer);
  }
  const auto first = static_cast<std::uint32_t>(scene.vertices.size());
  const auto firstTriangle = static_cast<std::uint32_t>(scene.triangles.size());
  for (const glm::dvec3& p : points) scene.vertices.push_back(placement.apply(p));
  for (const auto& f : faces) addFace(scene, first + f[0], first + f[1], first + f[2]);
  closeMesh(scene, firstTriangle, material, "icosphere");
}

MeshTopology meshTopology(const Scene& scene, const Mesh& mesh) {
  MeshTopology topology;
  topology.vertexTriangles.resize(scene.vertices.size());
  topology.onBoundary.assign(scene.vertices.size(), false);
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::size_t> edgeIndex;
  for (std::uint32_t t = mesh.firstTriangle; t < scene.meshEnd(mesh); ++t) {
    const Triangle& tri = scene.triangles[t];
    for (int k = 0; k < 3; ++k) {
      topology.vertexTriangles[tri.vertex[k]].push_back(t);
      const std::uint32_t a = std::min(tri.vertex[k], tri.vertex[(k + 1) % 3]);
      const std::uint32_t b = std::max(tri.vertex[k], tri.vertex[(k + 1) % 3]);
      auto [it, inserted] = edgeIndex.try_emplace({a, b}, topology.edges.size());
      if (inserted) topology.edges.push_back({a, b, {}});
      topology.edges[it->second].triangles.push_back(t);
    }
  }
  for (const MeshTopology::Edge& e : topology.edges)
    if (e.triangles.size() < 2) topology.onBoundary[e.a] = topology.onBoundary[e.b] = true;
  return topology;
}

}  // namespace rayview::testing
