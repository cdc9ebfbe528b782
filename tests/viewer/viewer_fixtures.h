#pragma once
// What the viewer's logic tests share: the test scene, a loaded session's parts, scratch directories.

#include <filesystem>
#include <fstream>
#include <memory>
#include <string>

#include "rayview/scene_loader.h"
#include "scene_session.h"
#include "support/image_compare.h"

namespace rayview::viewer_testing {

namespace fs = std::filesystem;

inline fs::path freshDirectory(const std::string& name) {
  const fs::path directory = testing::testOutputDirectory() / "viewer_logic" / name;
  fs::remove_all(directory);
  fs::create_directories(directory);
  return directory;
}

inline void writeText(const fs::path& path, const std::string& text) { std::ofstream(path) << text; }

inline const fs::path kViewerScene = testing::sourceDirectory() / "tests/viewer/viewer_scene.xml";

inline LoadedSceneParts loadParts() {
  LoadedScene loaded = loadSceneFile(kViewerScene);
  LoadedSceneParts parts;
  parts.scene = std::make_shared<const Scene>(std::move(loaded.scene));
  parts.geometry = prepareGeometry(parts.scene, AccelKind::Reference);
  parts.bounds = sceneBounds(*parts.scene);
  parts.accel = AccelKind::Reference;
  return parts;
}

}  // namespace rayview::viewer_testing
