#pragma once
// Primary rays exactly as SPEC section 3, in double precision, relative to the camera position.

#include <glm/vec3.hpp>

#include "rayview/scene.h"

namespace rayview {

struct CameraBasis {
  glm::dvec3 u{1, 0, 0}, v{0, 1, 0}, w{0, 0, 1};
};

// w = -normalize(gaze); u = normalize(up x w); v = w x u. Throws std::invalid_argument for a degenerate camera.
CameraBasis cameraBasis(const Camera& camera);

// Direction (not normalised) from the eye through the centre of pixel (column i, row j from the top): exactly
// pixelColumnPart(i) + pixelRowPart(j), so a renderer may keep the parts of its image's columns and rows.
glm::dvec3 pixelDirection(const Camera& camera, const CameraBasis& basis, double i, double j);
glm::dvec3 pixelColumnPart(const Camera& camera, const CameraBasis& basis, double i);  // to the near plane, across
glm::dvec3 pixelRowPart(const Camera& camera, const CameraBasis& basis, double j);     // down

// Empty when the camera is usable, else what is wrong with it ("gaze is zero", ...).
std::string cameraProblem(const Camera& camera);

}  // namespace rayview
