#include <cstdio>
#include <filesystem>
#include <system_error>

#include "model_commands.h"
#include "rayview/file_names.h"
#include "rayview/image.h"
#include "rayview/model_client.h"
#include "rayview/scene_open.h"
#include "rayview/scene_writer.h"
#include "texture_beside.h"

namespace rayview {
namespace {

namespace fs = std::filesystem;

bool endsInXml(const fs::path& path) {
  return lowerExtension(path) == ".xml";
}

bool sameFile(const fs::path& a, const fs::path& b) {
  std::error_code ec;
  const bool same = fs::equivalent(a, b, ec);
  return !ec && same;
}

// Each texture as a PNG beside the scene, which then names it. One outside the model's folder (named by its absolute
// path, model_materials.cpp) is copied only when asked, else the scene names it where it lies, relative to the
// scene's folder.
void writeTextures(Scene& scene, const fs::path& output, bool copyOutside, TexturesBeside& beside) {
  renameTextures(scene, [&](const std::string& name, const Texture& texture, bool) {
    const fs::path outside = fs::path(name).is_absolute() ? fs::path(name) : fs::path();
    if (!outside.empty() && !copyOutside) {
      std::error_code ec;
      const fs::path relative = outside.lexically_relative(fs::absolute(output.parent_path(), ec).lexically_normal());
      std::fprintf(stderr, "rayview: note: the scene names the texture where it lies, %s; --copy-textures copies it "
                   "beside the scene\n", outside.string().c_str());
      return relative.empty() ? outside.string() : relative.string();
    }
    // The model is never replaced: TexturesBeside passes over every name that exists.
    std::string written = beside.write(texture);
    if (!outside.empty())
      std::fprintf(stderr, "rayview: note: the texture %s is copied beside the scene as %s\n",
                   outside.string().c_str(), beside.written().back().string().c_str());
    return written;
  });
}

}  // namespace

int runImportCommand(const CommandLine& command) {
  const fs::path model = command.job.scene(), output = command.job.output;
  if (!endsInXml(output)) {
    std::fprintf(stderr, "rayview: error: the output must end in .xml: %s\n", output.c_str());
    return kExitBadInput;
  }
  if (sameFile(output, model)) {
    std::fprintf(stderr, "rayview: error: the output %s is the model; choose another name\n", output.string().c_str());
    return kExitBadInput;
  }
  ImportedModel imported;
  try {
    imported.loaded = openScene(model.string(), command.job.open, &imported.summary);
  } catch (const SceneError& error) {
    std::fprintf(stderr, "%s\n", error.what());
    return kExitBadInput;
  }
  for (const Diagnostic& warning : imported.loaded.warnings) std::fprintf(stderr, "%s\n", warning.format().c_str());
  Scene& scene = imported.loaded.scene;
  TexturesBeside beside(output);
  try {
    writeTextures(scene, output, command.copyTextures, beside);
    // Floats as floats (at most 9 significant digits): the handout's peers read them as float.
    writeFileAtomically(output, sceneToXml(scene.parameters(), scene.geometry(), scene.textureImage, NumberText::FloatWhenExact));
  } catch (const ImageIoError& error) {
    beside.removeAll();
    std::fprintf(stderr, "rayview: error: %s\n", error.what());
    return kExitIoFailure;
  }
  std::printf("%s: %s\n", output.string().c_str(), imported.summary.c_str());
  return kExitOk;
}

}  // namespace rayview
