#pragma once
// Small scenes built in code for unit tests: no file, no loader.

#include "rayview/scene.h"

namespace rayview::testing {

// Camera at the origin looking down -z, near plane [-1,1]^2 at distance 1, `size` x `size` pixels.
Camera frontCamera(int size);

// A matte white material (ka = kd = 1, ks = 0) unless changed.
Material plainMaterial(const std::string& id = "1");

// Appends the quad [x0,x1] x [y0,y1] at depth z (two CCW triangles facing +z) as a new mesh.
void addQuadFacingZ(Scene& scene, double x0, double y0, double x1, double y1, double z, std::uint32_t material);

// Appends triangle (a, b, c) as a one-face mesh.
void addTriangle(Scene& scene, const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c, std::uint32_t material);

}  // namespace rayview::testing
