#pragma once
// Two scenes' geometry equal, array by array (GoogleTest assertions): the scene writer's round trip and the
// loader's two readings (the big blocks as a stream, or the DOM) both need it.

#include "rayview/scene.h"

namespace rayview::testing {

// Vertices, texture coordinates, normals, meshes, triangles and the texture's pixels. Stops at the first
// differing array element (ASSERT inside), naming it.
void expectSameGeometry(const SceneGeometry& a, const SceneGeometry& b);

// The scene after the codec (rayview/scene_codec.h): its parameters and geometry encoded one after the other and
// decoded, every byte read (a test failure otherwise).
Scene throughTheCodec(const Scene& scene);

}  // namespace rayview::testing
