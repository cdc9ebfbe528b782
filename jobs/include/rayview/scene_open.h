#pragma once
// One way in: every command opens its input here, whatever it is (the embedded default scene, the handout's XML of
// any vintage, the METU CENG477 course's files with their cameras, or a model in any format the import worker reads),
// with one options value. The render, frames, batch, bench, import and export commands, the viewer and every rank
// under mpirun call openScene, so an option means the same thing everywhere.

#include <cstdint>
#include <string>
#include <vector>

#include "rayview/lean_memory.h"
#include "rayview/model_options.h"
#include "rayview/scene_loader.h"

namespace rayview {

struct SceneOpenOptions {
  bool strict = false;  // every repaired typo and unknown element is an error
  // Which camera to render, 1-based (a CENG477 file's <Cameras>); 0: the file's first (or, for a render into a
  // directory, every camera of a CENG477 file). A camera the input does not have is a located error.
  int camera = 0;
  ModelImportOptions model;            // a model's up axis and image size
  MemoryUse memory = MemoryUse::Auto;  // the render's memory layout (rayview/lean_memory.h)
  bool loadTexture = true;             // false: the texture's name only (planning, export of a scene's geometry)
};

// The input's kind by its name: the embedded default (""), a scene file (the handout's XML of any vintage or a
// CENG477 file: the loader tells them apart by their content), or a model (rayview/model_options.h, isModelFile).
enum class InputKind { DefaultScene, Scene, Model };
InputKind inputKindOf(const std::string& path);

// Throws SceneError (located, naming the file) when the input cannot be opened as asked. `summary`, when given, gets
// what opening made of the input: a model's "1234 triangles, 2 materials, ...; made up: ...; dropped: ...", a scene's
// counts.
// `threads`: how many the load may use (LoadOptions::threads), the job's own count.
LoadedScene openScene(const std::string& path, const SceneOpenOptions& options, std::string* summary = nullptr,
                      int threads = 1);

// The output names of a CENG477 file's cameras (<ImageName>, in order): one per camera, "" for a camera with none.
// Empty for any other input. Throws SceneError as openScene does.
std::vector<std::string> cameraImageNames(const std::string& path, const SceneOpenOptions& options);

}  // namespace rayview
