#include "rayview/scene_source.h"


namespace rayview {

LoadedScene loadSceneOrDefault(const std::string& path, const LoadOptions& options) {
  if (path.empty()) return loadSceneText(defaultSceneXml(), kDefaultSceneName, {}, options);
  return loadSceneFile(path, options);
}

}  // namespace rayview
