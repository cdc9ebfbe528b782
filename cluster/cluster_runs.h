#pragma once
// The two shapes of a render job on the ranks (private to cluster/): runJobOnRanks picks one.

#include <vector>

#include "rayview/frame_plan.h"

namespace rayview::cluster {

// Frames under MPI: rank 0 passes the frames still to render (its plan; `planCode` not kExitOk: the plan's error,
// printed), the other ranks nothing; rank 0 broadcasts them. A batch of at least as many scenes as ranks is dealt by
// scene (scene_batch.h: each scene loaded by rank 0 and built by the one rank that renders it). Otherwise the scene
// of consecutive frames is loaded once on every rank and its frames dealt as whole frames to the ranks while at
// least as many remain as there are ranks, the last ones as tiles to all ranks (frame_units.h). Rank 0 writes every
// frame. Under --enable-recovery a lost rank's scenes, frames and tiles go to the others; scene by scene, the job
// ends after that scene's frames (finished frames stay written; a rerun renders the rest).
int runClusterFrames(const RenderJob& job, const std::vector<FrameJob>& frames, int planCode);

// One image: rank 0 reads the scene, deals the tiles, renders too, writes the image and the summary.
int runClusterRender(const RenderJob& job);

}  // namespace rayview::cluster
