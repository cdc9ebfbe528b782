#pragma once
// The messages of a distributed render and the waits that never block on a rank that may be gone.

#include <mpi.h>

#include <chrono>
#include <cstdint>

namespace rayview::cluster {

enum Tag : int {
  kTagTile = 1,       // rank 0 -> worker: one int32, a tile index, or kNoMoreTiles
  kTagResult = 2,     // worker -> rank 0: TileResultHeader, then the tile's RGB rows
  kTagAlive = 3,      // worker -> rank 0, while it renders: nothing (a heartbeat)
  kTagLoadError = 4,  // worker -> rank 0: the text of its load error
};

inline constexpr std::int32_t kNoMoreTiles = -1;
// The same, and a rank was lost: end without MPI_Finalize, which would wait for it.
inline constexpr std::int32_t kNoMoreTilesRankLost = -3;

struct TileResultHeader {
  std::int32_t tile = 0;
  std::int32_t frame = 0;  // which of the job's frames: a late result of an earlier frame is dropped
  double busyMs = 0.0;
  std::uint64_t camera = 0, shadow = 0, reflection = 0;
};

// A worker rendering sends a heartbeat this often; rank 0 declares it lost after kLostAfter of silence while it
// holds tiles. A worker declares rank 0 lost after kRankZeroLostAfter without a tile or the end.
inline constexpr auto kAliveEvery = std::chrono::milliseconds(500);
inline constexpr auto kLostAfter = std::chrono::milliseconds(3000);
inline constexpr auto kRankZeroLostAfter = std::chrono::milliseconds(6000);
// How long a waiting rank sleeps between probes: short next to a tile, long next to a probe's cost.
inline constexpr auto kProbePause = std::chrono::microseconds(200);
inline constexpr auto kLongestProbePause = std::chrono::microseconds(2000);

// A message waiting from `source` (MPI_ANY_SOURCE) with `tag` (MPI_ANY_TAG)? Fills `status` when there is.
inline bool messageWaiting(int source, int tag, MPI_Status& status) {
  int flag = 0;
  return MPI_Iprobe(source, tag, MPI_COMM_WORLD, &flag, &status) == MPI_SUCCESS && flag != 0;
}

}  // namespace rayview::cluster
