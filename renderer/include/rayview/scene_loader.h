#pragma once
// Reading the handout's XML format, tolerant of its typos, located in its errors (SPEC section 2).

#include <cstddef>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "rayview/diagnostics.h"
#include "rayview/scene.h"

namespace rayview {

struct LoadOptions {
  bool strict = false;        // every repair and unknown element becomes an error
  bool loadTexture = true;    // read <textureimage> from disk
  // Read the big blocks (vertices, faces, normals, texture coordinates) as a stream, never holding the whole
  // text; false reads everything through tinyxml2's DOM. Both give the same scene, messages and warnings:
  // false is for tests and the fuzz target that check so.
  bool streamBlocks = true;
  // Which camera of a CENG477 file's <Cameras> to read, 1-based; 0 reads the first. Asking for a camera the file
  // does not have (any but the first of a CSE 461 file) is a located error.
  int camera = 0;
  // Threads the load may use (0: one per hardware thread): with two or more, a big file's faces are parsed on one
  // and its vertices, normals and texture coordinates on another. The same scene either way.
  int threads = 1;
};

struct LoadedScene {
  Scene scene;
  std::vector<Diagnostic> warnings;
  // A CENG477 file's cameras' <ImageName>s, one per camera in order ("" where a camera has none); empty for a file
  // of the handout's format, which has one camera and no output name.
  std::vector<std::string> cameraImageNames;
};

// Throws SceneError (with file:line) for anything that cannot be read as a whole scene.
LoadedScene loadSceneFile(const std::filesystem::path& path, const LoadOptions& options = {});

// `displayName` is what messages call the file; textures are looked up relative to `baseDirectory`.
LoadedScene loadSceneText(std::string_view xml, const std::string& displayName,
                          const std::filesystem::path& baseDirectory, const LoadOptions& options = {});

}  // namespace rayview
