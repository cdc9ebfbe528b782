#pragma once
// Where a scene comes from: a file the user named, or the embedded default when none was named.

#include <string>

#include "rayview/scene_loader.h"

namespace rayview {

// Throws SceneError (located) when the file cannot be read as a scene.
LoadedScene loadSceneOrDefault(const std::string& path, const LoadOptions& options);

}  // namespace rayview
