#include "rayview/scene_open.h"

#include <algorithm>
#include <cctype>
#include <fstream>

#include "rayview/model_client.h"
#include "rayview/scene_source.h"

namespace rayview {

InputKind inputKindOf(const std::string& path) {
  if (path.empty()) return InputKind::DefaultScene;
  return isModelFile(path) ? InputKind::Model : InputKind::Scene;
}

namespace {

LoadOptions loadOptionsOf(const SceneOpenOptions& options) {
  LoadOptions load;
  load.strict = options.strict;
  load.camera = options.camera;
  load.loadTexture = options.loadTexture;
  return load;
}

// A model holds one camera (its own or one made up for it): any other number is the same located error as a CENG477
// file's missing camera.
void checkModelCamera(const std::string& path, int camera) {
  if (camera > 1)
    throwSceneError({path, 0}, "camera " + std::to_string(camera) + " was asked for, but a model has 1 camera "
                               "(its own, or one made up for it)");
}

}  // namespace

LoadedScene openScene(const std::string& path, const SceneOpenOptions& options, std::string* summary, int threads) {
  if (inputKindOf(path) == InputKind::Model) {
    checkModelCamera(path, options.camera);
    ImportedModel model = importModel(path, options.model);
    if (summary) *summary = std::move(model.summary);
    return std::move(model.loaded);
  }
  LoadOptions load = loadOptionsOf(options);
  load.threads = threads;
  LoadedScene loaded = loadSceneOrDefault(path, load);
  if (summary)
    *summary = counted(loaded.scene.triangles.size(), "triangle") + ", " + std::to_string(loaded.scene.meshes.size()) +
               (loaded.scene.meshes.size() == 1 ? " mesh, " : " meshes, ") + counted(loaded.scene.materials.size(), "material");
  return loaded;
}

namespace {

// Whether the file's start names <Cameras> (any case), as a CENG477 file's does before its geometry: a handout file,
// which never does, is not parsed a second time to plan its one image.
bool mayHoldCameras(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::string start(64 * 1024, '\0');
  in.read(start.data(), static_cast<std::streamsize>(start.size()));
  start.resize(static_cast<std::size_t>(in.gcount()));
  std::transform(start.begin(), start.end(), start.begin(), [](unsigned char c) { return std::tolower(c); });
  return start.find("<cameras") != std::string::npos;
}

}  // namespace

std::vector<std::string> cameraImageNames(const std::string& path, const SceneOpenOptions& options) {
  if (inputKindOf(path) != InputKind::Scene || !mayHoldCameras(path)) return {};
  SceneOpenOptions quick = options;
  quick.loadTexture = false;
  return loadSceneOrDefault(path, loadOptionsOf(quick)).cameraImageNames;
}

}  // namespace rayview
