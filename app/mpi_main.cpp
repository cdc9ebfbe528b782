// libexec/rayview-mpi: `rayview render` on the ranks of an MPI job, and the viewer's workers. `rayview` becomes this
// program when it finds itself started by mpirun (app/mpi_handoff.h), so that a render outside MPI never loads libmpi.
#include <mpi.h>

#include <unistd.h>

#include <cstdio>
#include <string>
#include <vector>

#include "command_line.h"
#include "rayview/cluster.h"
#include "rayview/process_start.h"

namespace {

// Every rank reads the command line for its kind alone (a viewer's worker or a render); only rank 0 says what is wrong
// with it and sends the job on, so a refusal is printed once, as a single process prints it.
int runCommand(int rank, const std::vector<std::string>& arguments) {
  using namespace rayview;
  CommandLine command;
  int refusal = kExitOk;
  try {
    command = parseCommandLine(arguments);
  } catch (const UsageError& error) {
    if (rank == 0) std::fprintf(stderr, "rayview: error: %s\n", error.what());
    refusal = kExitBadInput;
  }
  // Rank 0 of a viewer job is the window (libexec/rayview-mpi-viewer); this program is every other rank.
  if (refusal == kExitOk && command.kind == CommandKind::View) return cluster::runViewWorker(command.job.threads);
  if (refusal == kExitOk && command.kind != CommandKind::Render) {
    if (rank == 0)
      std::fprintf(stderr, "rayview: error: under mpirun only `rayview render` and the viewer run on several ranks\n");
    refusal = kExitBadInput;
  }
  return cluster::runJobOnRanks(rank == 0 ? &command.job : nullptr, refusal);
}

}  // namespace

int main(int argc, char** argv) {
  using namespace rayview;
  captureProcessStart();
  int provided = 0;
  if (MPI_Init_thread(&argc, &argv, MPI_THREAD_FUNNELED, &provided) != MPI_SUCCESS) {
    std::fprintf(stderr, "rayview: error: MPI could not start\n");
    return kExitIoFailure;
  }
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  const int code = runCommand(rank, std::vector<std::string>(argv + 1, argv + argc));
  std::fflush(stdout);
  std::fflush(stderr);
  // With a rank gone, MPI_Finalize would wait for it: end here (the image, if any, is written whole already).
  if (cluster::peerLost()) ::_exit(code);
  MPI_Finalize();
  return code;
}
