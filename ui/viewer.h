#pragma once
// The viewer's entry point: what it needs to start, and running it.

#include <string>
#include <vector>

#include "rayview/knobs.h"

namespace rayview {

struct ViewerOptions {
  std::string scenePath;               // empty: the embedded default scene
  bool strict = false;                 // every repaired typo and unknown element is an error
  int threads = 0;                     // render threads; 0: one per hardware thread
  std::vector<KnobAssignment> knobs;   // written into the settings, and into the first scene's parameters
  std::string scriptPath;              // automation (docs/viewer.md); empty: none
  std::string comparePath;             // a reference image to compare the render with; empty: none
};

// Opens the window and runs until it closes; returns the exit status (rayview/exit_codes.h). Without a
// display, says so in one line (and how to render headless) and returns kExitIoFailure.
int runViewer(const ViewerOptions& options);

}  // namespace rayview
