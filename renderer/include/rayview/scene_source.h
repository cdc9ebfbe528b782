#pragma once
// Where a scene comes from: a file the user named, or the embedded default (scenes/default.xml, compiled
// in) when none was named.

#include <string>
#include <string_view>

#include "rayview/scene_loader.h"

namespace rayview {

inline constexpr const char* kDefaultSceneName = "default.xml (embedded)";

std::string_view defaultSceneXml();

// Throws SceneError (located) when the file cannot be read as a scene.
LoadedScene loadSceneOrDefault(const std::string& path, const LoadOptions& options);

}  // namespace rayview
