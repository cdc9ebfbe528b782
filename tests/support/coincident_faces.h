#pragma once
// Pixels that a scene leaves to chance: where the eye sees (directly or in a mirror) a face that is listed
// twice in the scene (the same three vertices, usually with opposite winding). The two copies lie at the
// same distance, so which one is "closest" — and so the colour, when their normals are opposite — is
// decided by rounding, and legitimately changes when the scene is scaled or moved.

#include <vector>

#include "rayview/image.h"
#include "rayview/scene.h"

namespace rayview::testing {

// Number of triangles that share their vertex set with another triangle.
std::size_t countDuplicatedFaces(const Scene& scene);

// One flag per pixel (row-major): the pixel's camera ray, or one of its mirror reflections up to the
// scene's depth, first meets a duplicated face. Traced with the reference traversal.
std::vector<bool> coincidentFacePixels(const Scene& scene);

// One flag per pixel: the pixel's camera ray passes through a boundary edge of a mesh (an edge of only
// one triangle), exactly in exact arithmetic (to a relative 1e-9). Whether such a ray hits the closed
// triangle is decided by rounding, and changes when the scene is scaled or moved. It happens when a
// scene's edge lines up with the pixel grid: dragon_lowres's mirror floor ends at z = -1, y = 0.055,
// exactly on the rays of one pixel row.
std::vector<bool> boundaryEdgePixels(const Scene& scene);

// Copies `expected` into `actual` where `mask` is set, so that a comparison skips those pixels.
void copyMaskedPixels(Image& actual, const Image& expected, const std::vector<bool>& mask);

}  // namespace rayview::testing
