#pragma once
// Scenes generated in code for benchmarks: sizes no hand-written file reaches.

#include "rayview/scene.h"

namespace rayview::bench {

// A rolling heightfield of about `triangles` triangles under a point light and a triangular light, with a
// mirror material on part of it, seen from above at `width` x `height`.
Scene heightfieldScene(int triangles, int width, int height);

// A UV sphere of about `triangles` triangles (per-vertex normals) on the same lights, filling most of the view.
Scene sphereScene(int triangles, int width, int height);

// `triangles` random, unconnected triangles in a cube (three vertices each, no sharing), sized so that their
// total area stays about the same at every count, seen from outside the cube. Deterministic (fixed seed).
Scene soupScene(int triangles, int width, int height);

// Vertex coordinates rounded to 6 decimals, as OBJ exporters write them: keeps written files to a realistic
// size (the shortest round-trip text of an unrounded double is 17 digits).
void roundCoordinates(Scene& scene);

}  // namespace rayview::bench
