#pragma once
// The frames of `rayview render --turntable N` and of a batch of scenes (`rayview render A.xml B.xml -o DIR/`):
// which files they go to, and which of those are still to be rendered.

#include <filesystem>
#include <string>
#include <vector>

#include "command_line.h"

namespace rayview {

struct FrameJob {
  std::string scenePath;
  int frame = 0;   // of a turntable: 0 .. frames - 1; a batch's scene: 0
  int frames = 0;  // 0: the scene's own camera
  std::filesystem::path output;
};

// Several frames or scenes: a turntable, more than one scene, or an output that is a directory.
bool isFrameCommand(const CommandLine& command);

// Every frame the command asks for, in order. Throws UsageError for an output that cannot name them (a turntable's
// needs one printf number, %d or %0Nd; a batch's is a directory, ending in '/').
std::vector<FrameJob> planFrames(const CommandLine& command);

// A frame's file is complete: it reads back as a whole image (files are written whole, so anything else is a file
// someone else left, or a crash of another program).
bool frameFileComplete(const std::filesystem::path& path);

}  // namespace rayview
