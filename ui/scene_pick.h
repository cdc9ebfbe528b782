#pragma once
// Picking: which triangle, mesh and material a pixel of the image shows. One camera ray through the pixel's
// centre, cast exactly as the tracer casts it, against the scene's traversal structure.

#include <cstdint>
#include <optional>
#include <string>

#include <glm/vec3.hpp>

#include "rayview/prepared_scene.h"
#include "rayview/scene.h"

namespace rayview {

struct PickResult {
  std::uint32_t triangle = 0;  // into SceneGeometry::triangles (0-based, in file order)
  std::uint32_t mesh = 0;      // into SceneGeometry::meshes
  std::uint32_t material = 0;  // into SceneParameters::materials
  glm::dvec3 point{0.0};       // the hit, in world coordinates
};

// The first surface pixel (column i, row j from the top) of `camera`'s image shows; nothing for the background,
// a pixel outside the image or a camera that cannot be rendered.
std::optional<PickResult> pickPixel(const Camera& camera, const PreparedGeometry& geometry, int i, int j);

// "picked mesh=ID material=ID triangle=N", the line printed on stdout (ids as in the file).
std::string describePick(const PickResult& pick, const SceneGeometry& geometry, const SceneParameters& parameters);

}  // namespace rayview
