#pragma once
// The bookkeeping every dealer of work to ranks shares (tiles and whole frames, scenes, the viewer's passes): who is
// lost, when each worker was last heard from and last sent to, and one rule for silence. A worker holding work that
// is silent for kLostAfter is lost (its work is the dealer's to deal again); an idle one hears from rank 0 every
// kNudgeEvery, so that its own watch on rank 0 stays quiet. A loss is noted once for the job (notePeerLost), which
// then ends without MPI_Finalize.

#include <chrono>
#include <functional>
#include <vector>

#include "mpi_link.h"
#include "tile_exchange.h"

namespace rayview::cluster {

// An idle worker hears from rank 0 this often.
inline constexpr auto kNudgeEvery = std::chrono::milliseconds(1000);

class WorkerWatch {
 public:
  using Clock = std::chrono::steady_clock;

  explicit WorkerWatch(int ranks, const std::vector<bool>& lostBefore = {})
      : lost_(static_cast<std::size_t>(ranks), false), lastHeard_(static_cast<std::size_t>(ranks), Clock::now()),
        lastSent_(static_cast<std::size_t>(ranks), Clock::now()) {
    for (std::size_t r = 0; r < lostBefore.size() && r < lost_.size(); ++r) lost_[r] = lostBefore[r];
  }

  int ranks() const { return static_cast<int>(lost_.size()); }
  bool lost(int worker) const { return lost_[static_cast<std::size_t>(worker)]; }
  const std::vector<bool>& lostRanks() const { return lost_; }

  // `worker` was given work while it held none: its silence counts from now, not from its last word.
  void startedHolding(int worker) { lastHeard_[static_cast<std::size_t>(worker)] = Clock::now(); }
  void heard(int worker) { lastHeard_[static_cast<std::size_t>(worker)] = Clock::now(); }
  void sent(int worker) { lastSent_[static_cast<std::size_t>(worker)] = Clock::now(); }

  // Marks `worker` lost and notes the job's loss; false when it was lost already (nothing to deal again).
  bool lose(int worker) {
    if (lost(worker)) return false;
    lost_[static_cast<std::size_t>(worker)] = true;
    notePeerLost();
    return true;
  }

  // For each worker not lost: `onSilent` when it holds work (`holds`) and has been silent past kLostAfter, else
  // `onIdle` when it holds none and has heard nothing from rank 0 for kNudgeEvery; `onIdle` may deal it work.
  void watch(const std::function<bool(int)>& holds, const std::function<void(int)>& onSilent,
             const std::function<void(int)>& onIdle) {
    const auto now = Clock::now();
    for (int w = 1; w < ranks(); ++w) {
      if (lost(w)) continue;
      const bool holding = holds(w);
      if (holding && now - lastHeard_[static_cast<std::size_t>(w)] > kLostAfter) onSilent(w);
      else if (!holding && now - lastSent_[static_cast<std::size_t>(w)] > kNudgeEvery) onIdle(w);
    }
  }

 private:
  std::vector<bool> lost_;
  std::vector<Clock::time_point> lastHeard_, lastSent_;
};

}  // namespace rayview::cluster
