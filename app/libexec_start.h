#pragma once
// Starting the programs in `libexec/` beside the `rayview` executable: the viewer (the window's libraries) and the
// MPI renderer (libmpi), so a headless command never loads them. An exec keeps the process id, arguments, streams
// and signal dispositions: a caller sees one process.

#include <string>

namespace rayview {

// Becomes `libexec/NAME` with `argv`. Returns only when that is impossible, with a one-line reason.
std::string execLibexecProgram(const char* name, char** argv);

// Becomes `libexec/rayview-viewer`; returns the reason when it cannot (missing, or a build without the viewer).
std::string startViewerProgram(char** argv);

}  // namespace rayview
