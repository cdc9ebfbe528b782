#pragma once
// The viewer's entry point (implemented in ui/, linked when rayview is built with the viewer).

#include "command_line.h"

namespace rayview {

// Opens the window on command.scenePath (the embedded default scene when empty) and runs until it closes.
// Without a display: one line on stderr saying so and how to render headless instead, and exit code 1.
// Returns the process exit code.
int runViewer(const CommandLine& command);

}  // namespace rayview
