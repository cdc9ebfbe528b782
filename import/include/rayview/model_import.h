#pragma once
// Reading a model file into a scene and writing a scene as a model, with Assimp (and rayview's own readers for
// OBJ with MTL, binary and ASCII PLY and STL, which are faster and exact). Only the import worker (libexec/rayview-import), the tests and
// the benchmarks link this; rayview itself opens models through rayview/model_client.h.

#include <filesystem>
#include <string>
#include <vector>

#include "rayview/model_options.h"
#include "rayview/scene.h"

namespace rayview {

struct ModelScene {
  Scene scene;                        // camera, lights and materials made up where the file has none
  std::vector<std::string> warnings;  // about the whole file
  std::string summary;                // triangles, meshes, materials, texture, what was made up and dropped
};

// Throws SceneError naming the file (line 0) for anything that cannot be read as a whole, finite model.
ModelScene readModel(const std::filesystem::path& path, const ModelImportOptions& options);

// The geometry only, as the file gives it (no framing, materials or texture): what the benchmarks time.
// `viaAssimp` forces Assimp for the formats rayview reads itself.
SceneGeometry readModelGeometry(const std::filesystem::path& path, bool viaAssimp);

// Writes the scene's geometry and materials as `output` (.obj with its .mtl, .ply, .stl, .gltf with its .bin,
// .glb), each file whole or not at all. Throws SceneError naming `output` when it cannot.
void exportScene(const Scene& scene, const std::filesystem::path& output);

}  // namespace rayview
