#include <mpi.h>

#include <cstdint>
#include <cstdio>
#include <vector>

#include "cluster_runs.h"
#include "mpi_link.h"
#include "rayview/cluster.h"
#include "rayview/exit_codes.h"

namespace rayview::cluster {
namespace {

// Rank 0's job (or its refusal) to every rank. Returns kExitOk with `out` set, or the refusal.
int shareJob(int rank, const RenderJob* job, int refusal, RenderJob& out) {
  std::vector<std::uint8_t> bytes;
  std::int64_t header[2] = {refusal, 0};
  if (rank == 0 && refusal == kExitOk) {
    bytes = encodeRenderJob(*job);
    header[1] = static_cast<std::int64_t>(bytes.size());
  }
  broadcastGently(header, 2, MPI_INT64_T);
  if (header[0] != kExitOk) return static_cast<int>(header[0]);
  bytes.resize(static_cast<std::size_t>(header[1]));
  broadcastGently(bytes.data(), static_cast<int>(bytes.size()), MPI_BYTE);
  out = rank == 0 ? *job : decodeRenderJob(bytes);
  return kExitOk;
}

}  // namespace

int runJobOnRanks(const RenderJob* job, int refusal) {
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  RenderJob shared;
  if (const int code = shareJob(rank, job, refusal, shared); code != kExitOk) return code;
  if (!isFrameJob(shared)) return runClusterRender(shared);
  // Rank 0 plans the frames: only it sees the output directory.
  std::vector<FrameJob> pending;
  int planCode = kExitOk;
  if (rank == 0) {
    std::size_t asked = 0;
    planCode = pendingFrames(shared, pending, asked);
    if (planCode == kExitOk && !shared.quiet)
      std::printf("frames     %zu asked, %zu complete already, %zu to render\n", asked, asked - pending.size(),
                  pending.size());
  }
  return runClusterFrames(shared, pending, planCode);
}

}  // namespace rayview::cluster
