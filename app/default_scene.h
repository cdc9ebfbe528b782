#pragma once
// The scene rayview shows when no file is given (scenes/default.xml, compiled in).

#include <string_view>

namespace rayview {

inline constexpr const char* kDefaultSceneName = "default.xml (embedded)";

std::string_view defaultSceneXml();

}  // namespace rayview
