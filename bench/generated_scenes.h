#pragma once
// Scenes generated in code for benchmarks: sizes no hand-written file reaches.

#include "rayview/scene.h"

namespace rayview::bench {

// A rolling heightfield of about `triangles` triangles under a point light and a triangular light, with a
// mirror material on part of it, seen from above at `width` x `height`.
Scene heightfieldScene(int triangles, int width, int height);

}  // namespace rayview::bench
