#pragma once
// `rayview render` of several frames: a turntable (--turntable N) or a batch of scenes into a directory. Frames
// whose file is already complete are skipped (--overwrite renders them), so a rerun finishes an interrupted job.

#include <vector>

#include "command_line.h"
#include "frame_plan.h"

namespace rayview {

// The frames still to render (all with `overwrite`), of `asked`; each output is checked before any frame is
// rendered, so nothing is written for a bad command. Returns kExitOk or the exit code (the message printed).
int pendingFrames(const CommandLine& command, std::vector<FrameJob>& pending, std::size_t& asked);

// Returns the process exit code (kExitOk, kExitBadInput, kExitIoFailure).
int runFramesCommand(const CommandLine& command);

}  // namespace rayview
