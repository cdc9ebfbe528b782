// rayview-cli and rayview-viewer (started by the launcher `rayview`, app/launcher.cpp): the viewer by default,
// `rayview render` headless, `rayview bench`, `rayview compare`. rayview-cli has no viewer: it hands the viewer
// command to rayview-viewer.
#include <cstdio>
#include <string>
#include <vector>

#include "bench_command.h"
#include "command_line.h"
#include "compare_command.h"
#include "model_commands.h"
#include "process_start.h"
#include "program_exec.h"
#include "render_command.h"

#ifdef RAYVIEW_HAVE_VIEWER
#include "viewer.h"
#endif

int main(int argc, char** argv) {
  using namespace rayview;
  captureProcessStart();
  CommandLine command;
  try {
    command = parseCommandLine(std::vector<std::string>(argv + 1, argv + argc));
  } catch (const UsageError& error) {
    std::fprintf(stderr, "rayview: error: %s\n", error.what());
    return kExitBadInput;
  }
  switch (command.kind) {
    case CommandKind::Help:
      std::fputs(helpText(command.helpFor).c_str(), stdout);
      return kExitOk;
    case CommandKind::Version:
      std::fputs(versionText().c_str(), stdout);
      return kExitOk;
    case CommandKind::Render:
      return runRenderCommand(command);
    case CommandKind::Bench:
      return runBenchCommand(command);
    case CommandKind::Compare:
      return runCompareCommand(command);
    case CommandKind::Import:
      return runImportCommand(command);
    case CommandKind::Export:
      return runExportCommand(command);
    case CommandKind::View:
#ifdef RAYVIEW_HAVE_VIEWER
      return runViewer(ViewerOptions{command.scenePath, command.strict, command.threads, command.knobs,
                                     command.scriptPath, command.comparePath});
#else
      execSiblingProgram("rayview-viewer", argv);
      // Built without the viewer: render the scene headless instead and say where the image went.
      command.kind = CommandKind::Render;
      command.outputPath = "rayview-default.png";
      return runRenderCommand(command);
#endif
  }
  return kExitOk;
}
