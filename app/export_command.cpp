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

// Whether a material shows the texture named `name` (the scene's own when `sceneTexture`) in a file of `output`'s
// format: glTF keeps metallic-roughness maps, OBJ's MTL has no place for them; both keep cut-outs' images.
bool shown(const Scene& scene, const std::string& name, bool sceneTexture, const fs::path& output) {
  const bool metalRough = lowerExtension(output) != ".obj";
  return std::any_of(scene.materials.begin(), scene.materials.end(), [&](const Material& m) {
    if (!sceneTexture && m.emits() && m.emissionImage == name) return true;
    if (!sceneTexture && metalRough && m.metalRoughImage == name) return true;
    if (!sceneTexture && m.alphaImage == name) return true;
    return m.textureFactor != 0.0f && (sceneTexture ? m.textureImage.empty() : m.textureImage == name);
  });
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
  TexturesBeside beside(output);
  try {
    LoadedScene loaded = openScene(input, command.job.open, nullptr, command.job.threads);
    for (const Diagnostic& warning : loaded.warnings) std::fprintf(stderr, "%s\n", warning.format().c_str());
    Scene& scene = loaded.scene;
    // The names the exported materials give their textures, relative to the model; none when there is no file to
    // name, or no material shows it.
    renameTextures(scene, [&](const std::string& name, const Texture& texture, bool isScenes) {
      return takesTextures(output) && shown(scene, name, isScenes, output) ? beside.write(texture) : "";
    });
    exportOpenedScene(scene, output);
  } catch (const SceneError& error) {
    beside.removeAll();
    std::fprintf(stderr, "%s\n", error.what());
    return kExitBadInput;
  } catch (const ModelWriteError& error) {
    beside.removeAll();
    std::fprintf(stderr, "rayview: error: %s\n", error.what());
    return kExitIoFailure;
  } catch (const ImageIoError& error) {
    beside.removeAll();
    std::fprintf(stderr, "rayview: error: %s\n", error.what());
    return kExitIoFailure;
  }
  std::string written;
  for (const fs::path& file : beside.written()) written += (written.empty() ? "" : ", ") + file.string();
  std::printf("%s: written from %s%s\n", output.c_str(), input.c_str(),
              written.empty() ? ""
              : (beside.written().size() == 1 ? ", its texture as " + written : ", its textures as " + written).c_str());
  return kExitOk;
}

}  // namespace rayview
