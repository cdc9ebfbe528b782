#pragma once
// How long the ranks of a distributed render wait for one another. No MPI here: the dealer's bookkeeping
// (work_dealer.h) uses them and is tested without MPI.

#include <chrono>

namespace rayview::cluster {

// A worker rendering sends a heartbeat this often; rank 0 declares it lost after kLostAfter of silence while it
// holds tiles. A worker declares rank 0 lost after kRankZeroLostAfter without a tile or the end.
inline constexpr auto kAliveEvery = std::chrono::milliseconds(500);
inline constexpr auto kLostAfter = std::chrono::milliseconds(3000);
inline constexpr auto kRankZeroLostAfter = std::chrono::milliseconds(6000);
// An idle worker hears from rank 0 this often, so that its own watch on rank 0 stays quiet.
inline constexpr auto kNudgeEvery = std::chrono::milliseconds(1000);
// How long a waiting rank sleeps between probes: short next to a tile, long next to a probe's cost.
inline constexpr auto kProbePause = std::chrono::microseconds(200);
inline constexpr auto kLongestProbePause = std::chrono::microseconds(2000);

}  // namespace rayview::cluster
