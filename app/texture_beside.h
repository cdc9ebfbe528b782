#pragma once
// The textures a written scene or model names, as PNGs beside it (`import`, `export`).

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "rayview/scene.h"

namespace rayview {

// Writes textures as PNGs beside one output file, each whole under a name no file has: OUTPUT-STEM_texture.png,
// then OUTPUT-STEM_texture-N.png. A command never replaces a file it did not write; when a user's file holds a name,
// it says which name it took instead.
class TexturesBeside {
 public:
  explicit TexturesBeside(std::filesystem::path output) : output_(std::move(output)) {}

  // Writes `texture` (ImageIoError when it cannot); returns its name as the written file names it.
  std::string write(const Texture& texture);
  const std::vector<std::filesystem::path>& written() const { return written_; }
  // Removes every file written, when the rest of the command failed.
  void removeAll();

 private:
  std::string freeName() const;

  std::filesystem::path output_;
  std::vector<std::filesystem::path> written_;
};

// Gives each texture of the scene a new name, `place(name, image, isScenes)`: the scene's own (isScenes true) and
// each material's, the materials renamed to match. A texture that was never read, or that `place` names "", is dropped, and with it the
// texture of the materials that showed it.
using TexturePlace = std::function<std::string(const std::string& name, const Texture& image, bool isScenes)>;
void renameTextures(Scene& scene, const TexturePlace& place);

}  // namespace rayview
