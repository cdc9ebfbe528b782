#pragma once
// Opening models through the import worker (libexec/rayview-import), a child process: Assimp is never loaded into
// rayview itself (start-up, and a crash on a malformed file ends the child, not rayview).

#include <filesystem>
#include <stdexcept>
#include <string>

#include "rayview/model_options.h"
#include "rayview/scene_loader.h"

namespace rayview {

struct ImportedModel {
  LoadedScene loaded;   // the scene, as the XML loader would return it; sourcePath is the model file
  std::string summary;  // "1234 triangles, 2 meshes, 2 materials, texture wood.png; made up: ...; dropped: ..."
};

// Throws SceneError naming the file for a model that cannot be read, and for a worker that dies or answers
// garbage.
ImportedModel importModel(const std::filesystem::path& path, const ModelImportOptions& options);
LoadedScene loadModelScene(const std::filesystem::path& path, const ModelImportOptions& options = {});

// Writes the geometry and materials of an opened scene (rayview/scene_open.h: any input) as `outputPath` (.obj, .ply,
// .stl, .gltf, .glb), whole or not at all, through the worker, which holds the exporters: the scene reaches it in the
// one scene codec. Throws SceneError naming the scene's file for a failed export, ModelWriteError when the files could
// not be written (a full disk, no permission): the old files are then as they were.
struct ModelWriteError : std::runtime_error {
  using std::runtime_error::runtime_error;
};
void exportOpenedScene(const Scene& scene, const std::filesystem::path& outputPath);

// The worker's path: $RAYVIEW_IMPORT_WORKER, else libexec/rayview-import beside the running executable, else the
// build tree's (for tests).
std::filesystem::path importWorkerPath();

}  // namespace rayview
