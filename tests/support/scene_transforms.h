#pragma once
// Whole-scene transformations for the numerical-extremes tests: the same picture at another scale or place.

#include <glm/vec3.hpp>

#include "rayview/scene.h"

namespace rayview::testing {

// Scales every position about the world origin by `factor`: vertices, camera position, near plane
// (l, r, b, t) and near distance, light positions and triangular-light vertices. Light intensities are
// multiplied by factor^2 so that irradiance I / d^2 is unchanged (right for point lights and the `area`
// triangular-light model, whose light falls off with distance). A <shadowrayepsilon> is a length and is
// scaled with the rest. Normals, colours and materials are unchanged. The rendered image stays the same in
// exact arithmetic.
void scaleScene(Scene& scene, double factor);

// Moves every position (vertices, camera, lights) by `offset`. The rendered image stays the same in exact
// arithmetic.
void translateScene(Scene& scene, const glm::dvec3& offset);

// Divides the image resolution by `divisor` (at least one pixel each way). The frustum is unchanged, so the
// image is a coarser sampling of the same view.
void reduceResolution(Scene& scene, int divisor);

}  // namespace rayview::testing
