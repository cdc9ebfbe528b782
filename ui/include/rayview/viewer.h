#pragma once
// The viewer's entry point: what it needs to start, and running it.

#include <memory>
#include <string>
#include <vector>

#include "rayview/knobs.h"
#include "rayview/pass_farm.h"
#include "rayview/scene_open.h"

namespace rayview {

struct ViewerOptions {
  std::string scenePath;               // empty: the embedded default scene
  SceneOpenOptions open;               // how every scene is opened (--strict, --camera, --up, ...)
  int threads = 0;                     // render threads; 0: one per hardware thread
  std::vector<KnobAssignment> knobs;   // written into the settings, and into the first scene's parameters
  std::string scriptPath;              // automation (docs/viewer.md); empty: none
  std::string comparePath;             // a reference image to compare the render with; empty: none
  // Who traces the passes when not this process's threads (the other ranks of an MPI job); null: these threads.
  std::shared_ptr<PassFarm> farm;
};

// How the viewer ended; the command line maps it onto its exit statuses.
enum class ViewerExit {
  Ok,        // the window was closed, or the script finished
  BadInput,  // the script could not be read or parsed
  Failed,    // no display, or the script failed
};

// Opens the window and runs until it closes. Without a display, says so in one line (and how to render
// headless) and returns ViewerExit::Failed.
ViewerExit runViewer(const ViewerOptions& options);

}  // namespace rayview
