#pragma once
// Rendering under mpirun (docs/scale-out.md): what the programs in app/ call, between MPI_Init_thread
// (MPI_THREAD_FUNNELED at least; the viewer's rank 0 MPI_THREAD_SERIALIZED) and MPI_Finalize.

#include <memory>

#include "rayview/pass_farm.h"
#include "rayview/render_job.h"

namespace rayview::cluster {

// Every rank of `mpirun -n N rayview render ...`. Rank 0 passes the job its command line gave, or, with `refusal` not
// kExitOk, the command line's exit code (its message printed); the other ranks pass nullptr and receive the job from
// rank 0 as bytes (encodeRenderJob), so only rank 0 reads the command line, the inputs and the output directory.
// Then every rank runs its share: one image's tiles, or frames (rank 0 plans them) dealt as scenes, whole frames or
// tiles. Rank 0 writes every file and prints what a single process prints. Returns this rank's exit code.
int runJobOnRanks(const RenderJob* job, int refusal);

// A rank other than 0 of `mpirun -n N rayview [SCENE]`: traces the passes of the viewer on rank 0 until its window
// closes. Returns this rank's exit code.
int runViewWorker(int threads);

// Rank 0 of the viewer: the farm that deals its passes to the other ranks.
class ViewerPassFarm : public PassFarm {
 public:
  // Tells every worker to end and waits (a few seconds at most) until each has said goodbye. Call once the viewer,
  // and with it the renderer's controller thread, is gone.
  virtual void shutdown() = 0;
};
std::shared_ptr<ViewerPassFarm> makeViewerFarm(int ranks, int threads);

// A rank was lost during the job: MPI_Finalize would wait for it, so the program ends without it.
bool peerLost();

}  // namespace rayview::cluster
