// Replacing this process with one of rayview's programs, which sit beside the running executable.
//
// The launcher (`rayview`) starts `rayview-cli`; `rayview-cli` starts `rayview-viewer` for the viewer. Each is
// an exec: the same process id, arguments, standard streams and signal dispositions, so a caller (a shell,
// a test, a window manager) sees one process. Plain C calls only: the launcher links nothing else.
#pragma once

#include <limits.h>
#include <unistd.h>

#include <cstring>

namespace rayview {

// The path of `program` in the directory of /proc/self/exe, into `path`; false if it does not fit.
inline bool siblingProgramPath(const char* program, char (&path)[PATH_MAX]) {
  const ssize_t length = ::readlink("/proc/self/exe", path, sizeof path - 1);
  if (length <= 0) return false;
  path[length] = '\0';
  char* slash = std::strrchr(path, '/');
  const std::size_t directory = slash ? static_cast<std::size_t>(slash - path) + 1 : 0;
  if (directory + std::strlen(program) + 1 > sizeof path) return false;
  std::memcpy(path + directory, program, std::strlen(program) + 1);
  return true;
}

// Runs `program` (a sibling) with `argv`; returns only if it could not (errno says why).
inline void execSiblingProgram(const char* program, char** argv) {
  char path[PATH_MAX];
  if (siblingProgramPath(program, path)) ::execv(path, argv);
}

}  // namespace rayview
