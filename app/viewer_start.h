#pragma once
// Starting the viewer from `rayview`: the window's libraries live in `libexec/rayview-viewer` beside the
// executable, which this process becomes by exec, so a headless command never loads them.

#include <string>

namespace rayview {

// Becomes `libexec/rayview-viewer` with `argv`. Returns only when that is impossible, with a one-line reason
// (the program is missing, or this build has no viewer).
std::string startViewerProgram(char** argv);

}  // namespace rayview
