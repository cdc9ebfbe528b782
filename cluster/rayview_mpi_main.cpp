// libexec/rayview-mpi: `rayview render` on the ranks of an MPI job. `rayview` becomes this program when it finds
// itself started by mpirun (app/mpi_handoff.h), so that a render outside MPI never loads libmpi.
#include <mpi.h>

#include <unistd.h>

#include <cstdio>
#include <string>
#include <vector>

#include "cluster_job.h"
#include "command_line.h"
#include "frames_command.h"
#include "process_start.h"
#include "tile_exchange.h"

namespace {

// Rank 0 plans the frames (only it sees the output directory); every rank renders them.
int runFrames(const rayview::CommandLine& command, const rayview::cluster::ClusterJob& job) {
  using namespace rayview;
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  std::vector<cluster::ClusterFrame> frames;
  int planCode = kExitOk;
  if (rank == 0) {
    std::vector<FrameJob> pending;
    std::size_t asked = 0;
    planCode = pendingFrames(command, pending, asked);
    for (const FrameJob& f : pending) frames.push_back({f.scenePath, f.frame, f.frames, f.output});
    if (planCode == kExitOk && !command.quiet)
      std::printf("frames     %zu asked, %zu complete already, %zu to render\n", asked, asked - pending.size(),
                  pending.size());
  }
  return cluster::runClusterFrames(job, frames, planCode);
}

// Rank 0 of a viewer job is the window (libexec/rayview-mpi-viewer); this program is every rank of a render job.
int runCommand(const rayview::CommandLine& command) {
  using namespace rayview;
  if (command.kind == CommandKind::View) return cluster::runViewWorker(command.threads);
  if (command.kind != CommandKind::Render) {
    std::fprintf(stderr, "rayview: error: under mpirun only `rayview render` and the viewer run on several ranks\n");
    return kExitBadInput;
  }
  const cluster::ClusterJob job{command.scenePath, command.outputPath, command.strict, command.quiet, command.threads,
                                command.knobs};
  if (isFrameCommand(command)) return runFrames(command, job);
  return cluster::runClusterRender(job);
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
  CommandLine command;
  int code = kExitOk;
  try {
    command = parseCommandLine(std::vector<std::string>(argv + 1, argv + argc));
  } catch (const UsageError& error) {
    std::fprintf(stderr, "rayview: error: %s\n", error.what());
    code = kExitBadInput;
  }
  if (code == kExitOk) code = runCommand(command);
  std::fflush(stdout);
  std::fflush(stderr);
  // With a rank gone, MPI_Finalize would wait for it: end here (the image, if any, is written whole already).
  if (cluster::peerLost()) ::_exit(code);
  MPI_Finalize();
  return code;
}
