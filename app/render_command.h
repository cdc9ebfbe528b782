#pragma once
// `rayview render`: load, build, render, write, report.

#include "command_line.h"

namespace rayview {

// Returns the process exit code (kExitOk, kExitBadInput, kExitIoFailure).
int runRenderCommand(const CommandLine& command);

}  // namespace rayview
