#pragma once
// Where a scene comes from: a file the user named, or the embedded default (scenes/default.xml, compiled
// in) when none was named.

#include <filesystem>
#include <string>
#include <string_view>

#include "rayview/scene_loader.h"

namespace rayview {

inline constexpr const char* kDefaultSceneName = "default.xml (embedded)";

std::string_view defaultSceneXml();

// Throws SceneError (located) when the file cannot be read as a scene.
LoadedScene loadSceneOrDefault(const std::string& path, const LoadOptions& options);

// Why writing `output` would destroy an input ("" when it would not): it is the scene file `scenePath`, or
// (once the scene is loaded) any file the process read (rayview/input_files.h: the texture image, loaded or not,
// a reference, a script) or any place the scene's texture could be, by any path (hard link, symlink, ./).
std::string outputOverwritesInput(const std::filesystem::path& output, const std::string& scenePath,
                                  const Scene* loaded);

// Why `output` cannot take a rendered image of `scenePath` ("" when it can): not .png or .ppm, or an input by any
// path (outputOverwritesInput). Checked by every command that renders before it starts work.
std::string renderOutputProblem(const std::filesystem::path& output, const std::string& scenePath);

}  // namespace rayview
