#pragma once
// `rayview bench tradeoff SCENE... --out DIR`: the speed-for-accuracy measurement of every scene, written as
// DIR/tradeoff.csv and DIR/<scene>_tradeoff.png, with a short table on stdout (docs/tradeoff.md).

#include "command_line.h"

namespace rayview {

// Returns the process exit code (kExitOk, kExitBadInput, kExitIoFailure).
int runBenchCommand(const CommandLine& command);

}  // namespace rayview
