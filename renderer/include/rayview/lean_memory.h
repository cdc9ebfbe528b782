#pragma once
// Scenes rendered lean: where a render's fixed costs would dominate its memory (the aim: at most 200 bytes a triangle
// from 100 000 triangles up). From 1e5 to 1e6 triangles the libraries (~4 MB), a 1920x1080 image (6.2 MB,
// and stb_image_write's filtered copy of it) and the heap's 2 MiB pages are as large as the scene itself
// (docs/PERFORMANCE.md, "The lean layout (opt-in)"). Rendered by `rayview render`, such a scene gets, at the
// cost of some speed (the viewer and the analysis, whose memory nothing bounds, keep Embree's speed):
// - rayview's packet BVH with leaves of up to kLeanLeafTriangles where Embree was asked for (prepareGeometry with
//   BuildPriority::Memory): its build adds ~40 bytes a triangle to the 1e5 soup's peak, Embree's ~120. Three, not
//   two or four: leaves of two took the 1e5 soup to 200 bytes a triangle, leaves of four cost its rays another 1.3x;
// - its image kept deflated in bands while it renders (renderFrameDeflated), made whole only
//   to be written, once the scene and its BVH are released;
// - a heap off huge pages from the moment the loader knows the scene's size
//   (LoadOptions::beforeArrays).
// From 1e6 triangles up the triangles' own memory dominates: Embree's compact layout keeps them under the limit at
// full speed.

#include <cstddef>

namespace rayview {

inline constexpr std::size_t kLeanFromTriangles = 100'000;
inline constexpr std::size_t kLeanUntilTriangles = 1'000'000;
inline constexpr std::size_t kLeanLeafTriangles = 3;

constexpr bool isLeanScene(std::size_t triangles) {
  return triangles >= kLeanFromTriangles && triangles < kLeanUntilTriangles;
}

}  // namespace rayview
