#pragma once
// The dealing of a distributed render's units (tiles, or whole frames): rank 0's coordinator (its main thread, the
// only one that calls MPI, while a thread of its own renders units too) and the workers' loop.

#include <cstddef>
#include <functional>
#include <vector>

#include "frame_units.h"
#include "rayview/image.h"
#include "rayview/thread_pool.h"
#include "rayview/tiles.h"
#include "rayview/tracer.h"

namespace rayview::cluster {

struct RankTally {
  double busyMs = 0.0;  // rendering tiles and whole frames
  std::size_t tiles = 0;
  std::size_t frames = 0;  // rendered whole
  std::size_t scenes = 0;  // of a batch dealt by scene: scenes rendered whole (scene_batch.h)
  RayCounts rays;
  bool lost = false;  // fell silent while it held tiles; they were dealt again
};

struct ExchangeResult {
  std::vector<RankTally> ranks;  // one per rank
  bool complete = false;         // every tile is in the image
};

// The tracer of a frame of the run (an index into it), called only by the thread that renders: rank 0's render
// thread, a worker's tile thread.
using TracerFor = std::function<const Tracer&(int frame)>;

// Rank 0: deals `units` to the other ranks and to its own render thread until every unit is placed in `assembly`
// (which hands each frame on as it completes) or a frame could not be written. Never blocks on another rank: a
// silent rank's units go to the others. `round` numbers the job's calls (a late result of an earlier one is
// dropped); `lost` (one per rank) carries the ranks lost in earlier rounds, and gains those lost in this one.
ExchangeResult coordinateUnits(const std::vector<WorkUnit>& units, FrameAssembly& assembly, int ranks,
                               ThreadPool& pool, const TracerFor& tracerFor, int round, std::vector<bool>& lost);

// Every other rank: renders the units rank 0 deals until it says there are no more. Returns the exit code
// (kExitIoFailure when rank 0 fell silent).
int workOnUnits(const std::vector<WorkUnit>& units, const TracerFor& tracerFor, int rank, ThreadPool& pool, int round);

// For the signal handler: units placed so far, and in all; of a run of frames, the frames written and asked.
std::size_t tilesPlaced();
std::size_t tilesPlanned();
void noteFrames(std::size_t written, std::size_t total);
std::size_t framesWritten();
std::size_t framesPlanned();  // 0: a single image

// Rank 0 stopped by a signal (mpirun ends the job so when a rank dies): the temporary file of the image being
// written goes, and one line says how far the job got.
void handleSignalsOnRankZero();

// Whether a rank of this job was lost (or, on a worker, rank 0 said so or fell silent): MPI_Finalize would
// wait for it for ever, so the process ends without it.
bool peerLost();
void notePeerLost();

}  // namespace rayview::cluster
