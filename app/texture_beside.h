#pragma once
// The texture a written scene or model names, as a PNG beside it (`import`, `export`).

#include <filesystem>
#include <string>

#include "rayview/scene.h"

namespace rayview {

// OUTPUT-STEM_texture.png, or when a file (the user's, perhaps the model's own texture) has that name, the first
// free OUTPUT-STEM_texture-N.png: a command never replaces a file it did not write, and says which name it took.
std::string freeTextureName(const std::filesystem::path& output);

// Writes `texture` whole under freeTextureName(output) (ImageIoError when it cannot); `name` gets the file's name
// as the written file should name it, and the path is returned, for removal should the rest fail.
std::filesystem::path writeTextureBeside(const Texture& texture, const std::filesystem::path& output, std::string& name);

}  // namespace rayview
