// runViewer(): from the command line to a running window, or one clear line when there is no display.
#include "rayview/viewer.h"

#include <cstdio>

#include "automation_script.h"
#include "viewer_app.h"

namespace rayview {
namespace {

ViewerExit noDisplay(const ViewerOptions& command, const std::string& why) {
  const std::string scene = command.scenePath.empty() ? "SCENE" : command.scenePath;
  std::fprintf(stderr, "rayview: no display (%s); to render without a window: rayview render %s -o out.png\n",
               why.c_str(), scene.c_str());
  return ViewerExit::Failed;
}

}  // namespace

ViewerExit runViewer(const ViewerOptions& command) {
  // The script is read and checked first: a typo fails before any window opens.
  std::optional<Script> script;
  if (!command.scriptPath.empty()) {
    try {
      script = readScriptFile(command.scriptPath);
    } catch (const ScriptError& error) {
      std::fprintf(stderr, "rayview: error: %s\n", error.what());
      return ViewerExit::BadInput;
    }
  }
  if (const std::string problem = Window::displayProblem(); !problem.empty()) return noDisplay(command, problem);
  try {
    ViewerApp app(command, std::move(script));
    return app.run() == 0 ? ViewerExit::Ok : ViewerExit::Failed;
  } catch (const DisplayUnavailable& error) {
    return noDisplay(command, error.what());
  }
}

}  // namespace rayview
