#include "libexec_start.h"

#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>

namespace rayview {

std::string execLibexecProgram(const char* name, char** argv) {
  std::error_code error;
  const std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", error);
  if (error) return "cannot find this executable's folder: " + error.message();
  const std::filesystem::path program = self.parent_path() / "libexec" / name;
  ::execv(program.c_str(), argv);
  return "cannot start " + program.string() + ": " + std::strerror(errno);
}

std::string startViewerProgram(char** argv) {
#ifdef RAYVIEW_NO_VIEWER
  static_cast<void>(argv);
  return "this rayview was built without the viewer (RAYVIEW_BUILD_VIEWER=OFF)";
#else
  return execLibexecProgram("rayview-viewer", argv);
#endif
}

}  // namespace rayview
