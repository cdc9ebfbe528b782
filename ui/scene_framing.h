#pragma once
// What F frames: the selected mesh, or else every mesh that is not a ground plane, so that a car standing on a
// huge floor fills the view instead of becoming a speck. Pure geometry (no GL), tested in orbit_camera_test.
//
// A ground plane is a flat mesh much larger than everything else: its bounding box's smallest extent is below
// kGroundFlatness of its largest, and its largest extent is more than kGroundDominance times the largest extent
// of the bounding box of all the other meshes together.

#include <cstddef>
#include <optional>
#include <vector>

#include "orbit_camera.h"
#include "rayview/scene.h"

namespace rayview {

inline constexpr double kGroundFlatness = 0.01;
inline constexpr double kGroundDominance = 4.0;

// The bounds of each mesh (of the vertices its triangles use), in the order of SceneGeometry::meshes.
std::vector<Bounds> meshBounds(const SceneGeometry& geometry);

// `mesh` is a ground plane of a scene whose other meshes have the bounds `rest`.
bool isGroundPlane(const Bounds& mesh, const Bounds& rest);

// The bounds F frames: the selected mesh's when there is one (and it has triangles); otherwise those of the meshes
// that are not ground planes; all meshes when every one is a ground plane.
Bounds framingBounds(const SceneGeometry& geometry, std::optional<std::size_t> selectedMesh);

}  // namespace rayview
