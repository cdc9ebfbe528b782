#include "support/conformance_scenes.h"

#include <algorithm>
#include <string>

#include "support/image_compare.h"

namespace rayview::testing {

std::vector<std::filesystem::path> conformanceScenePaths() {
  std::vector<std::filesystem::path> files;
  const std::filesystem::path dir = sharedDirectory() / "conformance" / "ceng477";
  if (!std::filesystem::is_directory(dir)) return files;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    const std::string name = entry.path().filename().string();
    if (entry.path().extension() == ".xml" && name.find(".ceng477.") == std::string::npos) files.push_back(entry.path());
  }
  std::sort(files.begin(), files.end());
  return files;
}

}  // namespace rayview::testing
