// Which files rayview reads itself rather than through Assimp: PLY and STL, by extension (faster than Assimp's
// readers, docs/dependencies.md, and they take files Assimp refuses, such as a PLY header after a blank line).

#include <algorithm>
#include <cctype>

#include "byte_input.h"
#include "model_parts.h"

namespace rayview::model {

void readPly(const std::string& bytes, const std::filesystem::path& path, SceneGeometry& g, Notes& notes);
bool readStl(const std::string& bytes, const std::filesystem::path& path, SceneGeometry& g);

bool readPlyOrStl(const std::filesystem::path& path, SceneGeometry& geometry, Notes& notes) {
  std::string extension = path.extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(), [](unsigned char c) { return std::tolower(c); });
  if (extension != ".ply" && extension != ".stl") return false;
  std::string problem;
  const std::string bytes = readWholeFile(path, problem);
  if (!problem.empty()) fail(path, problem);
  if (extension == ".ply") readPly(bytes, path, geometry, notes);
  else readStl(bytes, path, geometry);
  return true;
}

}  // namespace rayview::model
