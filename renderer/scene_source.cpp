#include "rayview/scene_source.h"

#include "rayview/file_read.h"
#include "rayview/image.h"
#include "rayview/input_files.h"
#include "rayview/texture_image.h"


namespace rayview {

LoadedScene loadSceneOrDefault(const std::string& path, const LoadOptions& options) {
  if (path.empty()) return loadSceneText(defaultSceneXml(), kDefaultSceneName, {}, options);
  return loadSceneFile(path, options);
}

std::string outputOverwritesInput(const std::filesystem::path& output, const std::string& scenePath,
                                  const Scene* loaded) {
  if (!scenePath.empty() && detail::sameFile(output, scenePath))
    return "the output " + output.string() + " is the scene file " + scenePath + "; choose another name";
  if (!loaded) return {};
  // Every file the load found, read or not (a texture that did not decode), and what the command read before it.
  if (std::string problem = outputReplacesInput(output); !problem.empty()) return problem;
  const Scene& scene = *loaded;
  // A texture the load did not look for (LoadOptions::loadTexture off) is the scene's all the same.
  const std::filesystem::path dir = scene.sourcePath.parent_path();
  auto isTexture = [&](const std::string& name) -> std::string {
    if (name.empty()) return {};
    for (const std::filesystem::path& candidate : detail::textureCandidates(dir.empty() ? "." : dir, name))
      if (detail::sameFile(output, candidate))
        return "the output " + output.string() + " is the scene's texture image " + candidate.string() +
               "; choose another name";
    return {};
  };
  if (std::string problem = isTexture(scene.textureImage); !problem.empty()) return problem;
  for (const Material& material : scene.materials)
    for (const std::string* name : material.images())
      if (std::string problem = isTexture(*name); !problem.empty()) return problem;
  return {};
}

std::string renderOutputProblem(const std::filesystem::path& output, const std::string& scenePath) {
  if (!isSupportedImageExtension(output)) return "the output must end in .png or .ppm: " + output.string();
  return outputOverwritesInput(output, scenePath, nullptr);
}

}  // namespace rayview
