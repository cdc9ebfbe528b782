#include "viewer_start.h"

#include <limits.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>

namespace rayview {

std::string startViewerProgram(char** argv) {
#ifdef RAYVIEW_NO_VIEWER
  static_cast<void>(argv);
  return "this rayview was built without the viewer (RAYVIEW_BUILD_VIEWER=OFF)";
#else
  std::error_code error;
  const std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", error);
  if (error) return "cannot find this executable's folder: " + error.message();
  const std::filesystem::path viewer = self.parent_path() / "libexec" / "rayview-viewer";
  ::execv(viewer.c_str(), argv);
  return "cannot start " + viewer.string() + ": " + std::strerror(errno);
#endif
}

}  // namespace rayview
