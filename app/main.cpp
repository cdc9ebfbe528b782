// `rayview` and `libexec/rayview-viewer`: the viewer by default, `rayview render` headless, `rayview bench`,
// `rayview compare`. `rayview` has no viewer: it becomes `libexec/rayview-viewer` for the viewer command.
#include <cstdio>
#include <new>
#include <string>
#include <vector>

#include "bench_command.h"
#include "command_line.h"
#include "compare_command.h"
#include "mpi_handoff.h"
#include "model_commands.h"
#include "rayview/process_start.h"
#include "rayview/image.h"
#include "rayview/render_job.h"

#ifdef RAYVIEW_HAVE_VIEWER
#include "rayview/viewer.h"
#else
#include "libexec_start.h"
#endif

namespace {

int runViewCommand(const rayview::CommandLine& command, char** argv) {
  using namespace rayview;
#ifdef RAYVIEW_HAVE_VIEWER
  static_cast<void>(argv);
  switch (runViewer(ViewerOptions{command.job.scene(), command.job.open, command.job.threads, command.job.knobs,
                                  command.scriptPath, command.comparePath, nullptr})) {
    case ViewerExit::Ok: return kExitOk;
    case ViewerExit::BadInput: return kExitBadInput;
    case ViewerExit::Failed: return kExitIoFailure;
  }
  return kExitIoFailure;
#else
  static_cast<void>(command);
  const std::string why = startViewerProgram(argv);
  std::fprintf(stderr, "rayview: error: the viewer cannot start: %s; to render without a window: rayview render %s -o out.png\n",
               why.c_str(), command.job.scene().empty() ? "SCENE" : command.job.scene().c_str());
  return kExitIoFailure;
#endif
}

}  // namespace

// A function-try-block: any command's allocation failure (an image, a BVH, a render's buffers, a worker's: the
// pool hands it back) ends in a message and a clean exit, never an abort; writes are whole or absent.
int main(int argc, char** argv) try {
  using namespace rayview;
  captureProcessStart();
  // Before any command writes a file: a signal that ends the process removes the file's temporary copy first.
  removeTemporaryFileOnSignals();
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
      if (const int code = handOffToMpi(argv); code >= 0) return code;
      return runRenderJob(command.job);
    case CommandKind::Bench:
      return runBenchCommand(command);
    case CommandKind::Compare:
      return runCompareCommand(command);
    case CommandKind::Import:
      return runImportCommand(command);
    case CommandKind::Export:
      return runExportCommand(command);
    case CommandKind::View:
      if (const int code = handOffViewerToMpi(argv); code >= 0) return code;
      return runViewCommand(command, argv);
  }
  return kExitOk;
} catch (const std::bad_alloc&) {
  std::fprintf(stderr, "rayview: error: out of memory: this needs more memory than the system gives it\n");
  return rayview::kExitOutOfMemory;
}
