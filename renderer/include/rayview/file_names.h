#pragma once
// What a file's name says of its kind: the extension, compared without regard to case (".OBJ" is ".obj").

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <string>

namespace rayview {

// The extension with its dot, in lower case: ".png", ".obj"; "" when there is none.
inline std::string lowerExtension(const std::filesystem::path& path) {
  std::string extension = path.extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(), [](unsigned char c) { return std::tolower(c); });
  return extension;
}

}  // namespace rayview
