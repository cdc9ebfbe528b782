#pragma once
// A batch of different scenes under MPI, dealt by scene (docs/scale-out.md, "Frames"): an idle rank gets the next
// scene whole; rank 0 reads each file as a single process does and sends the loaded scene, knobs applied, to that
// rank alone; the rank builds it, renders its frames and sends the pixels back; rank 0 renders scenes too and is
// the only writer.

#include <vector>

#include "rayview/frame_plan.h"
#include "rayview/frame_scene.h"
#include "rayview/thread_pool.h"
#include "scene_orders.h"
#include "tile_exchange.h"

namespace rayview::cluster {

// Rank 0: deals `runs` (scenes, each its frames of `frames`) until every frame is written, or a scene fails to
// load (the scenes before it are finished, then the located message is printed once) or a frame cannot be written.
// A rank silent for kLostAfter while holding a scene is lost and its scene goes back to the pile. Adds each rank's
// busy time, scenes and frames to `tally`. Returns the exit code, which it sends every worker too.
int dealScenes(const RenderJob& job, const std::vector<FrameJob>& frames, const std::vector<SceneRun>& runs,
               ThreadPool& pool, FrameProgress& progress, std::vector<RankTally>& tally);

// Every other rank: renders the scenes rank 0 sends until it says the batch is over. Returns the exit code rank 0
// sent (kExitIoFailure when rank 0 fell silent).
int workOnScenes(int rank, ThreadPool& pool);

}  // namespace rayview::cluster
