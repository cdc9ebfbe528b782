#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <system_error>

#include "model_commands.h"
#include "rayview/file_names.h"
#include "rayview/image.h"
#include "rayview/model_client.h"
#include "rayview/scene_open.h"
#include "texture_beside.h"

namespace rayview {
namespace {

namespace fs = std::filesystem;

// The formats whose materials name image files (OBJ's MTL, glTF's images); PLY and STL carry none.
bool takesTextures(const fs::path& output) {
  const std::string extension = lowerExtension(output);
  return extension == ".obj" || extension == ".gltf" || extension == ".glb";
}

bool usesTexture(const Scene& scene) {
  return scene.texture && std::any_of(scene.materials.begin(), scene.materials.end(),
                                      [](const Material& m) { return m.textureFactor != 0.0f; });
}

}  // namespace

// Any input the other commands open, opened the same way (a CENG477 file's camera, a model's up axis), then written
// by the import worker, which holds the exporters. The texture goes beside the model as a PNG it names, so the
// model opens anywhere as it looked here.
int runExportCommand(const CommandLine& command) {
  const std::string& input = command.job.scene();
  const fs::path& output = command.job.output;
  std::error_code ec;
  if (fs::equivalent(input, output, ec)) {
    std::fprintf(stderr, "rayview: error: the output %s is the scene file; choose another name\n", output.c_str());
    return kExitBadInput;
  }
  fs::path texture;
  try {
    LoadedScene loaded = openScene(input, command.job.open);
    for (const Diagnostic& warning : loaded.warnings) std::fprintf(stderr, "%s\n", warning.format().c_str());
    Scene& scene = loaded.scene;
    // The name the exported materials give the texture, relative to the model; none when there is no file to name.
    if (takesTextures(output) && usesTexture(scene))
      texture = writeTextureBeside(*scene.texture, output, scene.textureImage);
    else
      scene.textureImage.clear();
    exportOpenedScene(scene, output);
  } catch (const SceneError& error) {
    if (!texture.empty()) fs::remove(texture, ec);
    std::fprintf(stderr, "%s\n", error.what());
    return kExitBadInput;
  } catch (const ModelWriteError& error) {
    if (!texture.empty()) fs::remove(texture, ec);
    std::fprintf(stderr, "rayview: error: %s\n", error.what());
    return kExitIoFailure;
  } catch (const ImageIoError& error) {
    std::fprintf(stderr, "rayview: error: %s\n", error.what());
    return kExitIoFailure;
  }
  std::printf("%s: written from %s%s\n", output.c_str(), input.c_str(),
              texture.empty() ? "" : (", its texture as " + texture.string()).c_str());
  return kExitOk;
}

}  // namespace rayview
