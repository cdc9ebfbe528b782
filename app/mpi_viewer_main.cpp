// libexec/rayview-mpi-viewer: rank 0 of `mpirun -n N rayview [SCENE]`, the window, whose passes the other ranks
// (libexec/rayview-mpi) trace. `rayview` becomes this program on rank 0 (app/mpi_handoff.h), so that only the
// rank with the window loads GL and only MPI jobs load libmpi.
#include <mpi.h>

#include <unistd.h>

#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "command_line.h"
#include "rayview/cluster.h"
#include "rayview/process_start.h"
#include "rayview/viewer.h"

int main(int argc, char** argv) {
  using namespace rayview;
  captureProcessStart();
  int provided = 0;
  // The renderer's controller thread calls MPI while a pass renders, the main thread before and after.
  if (MPI_Init_thread(&argc, &argv, MPI_THREAD_SERIALIZED, &provided) != MPI_SUCCESS ||
      provided < MPI_THREAD_SERIALIZED) {
    std::fprintf(stderr, "rayview: error: MPI could not start with calls from more than one thread\n");
    return kExitIoFailure;
  }
  MPI_Comm_set_errhandler(MPI_COMM_WORLD, MPI_ERRORS_RETURN);
  int ranks = 1;
  MPI_Comm_size(MPI_COMM_WORLD, &ranks);
  int code = kExitOk;
  CommandLine command;
  try {
    command = parseCommandLine(std::vector<std::string>(argv + 1, argv + argc));
  } catch (const UsageError& error) {
    std::fprintf(stderr, "rayview: error: %s\n", error.what());
    code = kExitBadInput;
  }
  const auto farm = cluster::makeViewerFarm(ranks, command.job.threads);
  if (code == kExitOk) {
    std::printf("rendering on %d ranks: this window's and %d more\n", ranks, ranks - 1);
    std::fflush(stdout);
    ViewerOptions options{command.job.scene(), command.job.open, command.job.threads, command.job.knobs,
                          command.scriptPath, command.comparePath, farm};
    switch (runViewer(options)) {
      case ViewerExit::Ok: code = kExitOk; break;
      case ViewerExit::BadInput: code = kExitBadInput; break;
      case ViewerExit::Failed: code = kExitIoFailure; break;
    }
  }
  // Quitting ends every rank: the workers are told, and their goodbyes awaited.
  farm->shutdown();
  std::fflush(stdout);
  std::fflush(stderr);
  if (cluster::peerLost()) ::_exit(code);
  MPI_Finalize();
  return code;
}
