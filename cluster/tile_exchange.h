#pragma once
// The dealing of a distributed render's tiles: rank 0's coordinator (its main thread, the only one that calls
// MPI, while a thread of its own renders tiles too) and the workers' loop.

#include <cstddef>
#include <vector>

#include "rayview/image.h"
#include "rayview/thread_pool.h"
#include "rayview/tiles.h"
#include "rayview/tracer.h"

namespace rayview::cluster {

struct RankTally {
  double busyMs = 0.0;  // rendering tiles
  std::size_t tiles = 0;
  RayCounts rays;
  bool lost = false;  // fell silent while it held tiles; they were dealt again
};

struct ExchangeResult {
  std::vector<RankTally> ranks;  // one per rank
  bool complete = false;         // every tile is in the image
};

// Rank 0: deals `tiles` to the other ranks and to its own render thread until every tile is in `image`
// (width x height, already sized). Never blocks on another rank: a silent rank's tiles go to the others.
// `frame` numbers the job's frames (0 for a single image); `lost` (one per rank) carries the ranks lost in
// earlier frames, and gains those lost in this one.
ExchangeResult coordinateTiles(const Tracer& tracer, const std::vector<Tile>& tiles, int ranks, ThreadPool& pool,
                               Image& image, int frame, std::vector<bool>& lost);

// Every other rank: renders the tiles rank 0 deals until it says there are no more. Returns the exit code
// (kExitIoFailure when rank 0 fell silent).
int workOnTiles(const Tracer& tracer, const std::vector<Tile>& tiles, int rank, ThreadPool& pool, int frame);

// For the signal handler: tiles in the image so far, and in all.
std::size_t tilesPlaced();
std::size_t tilesPlanned();

// Whether a rank of this job was lost (or, on a worker, rank 0 said so or fell silent): MPI_Finalize would
// wait for it for ever, so the process ends without it.
bool peerLost();
void notePeerLost();

}  // namespace rayview::cluster
