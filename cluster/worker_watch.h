#pragma once
// What rank 0 knows of each worker, for every dealer of work (tiles and whole frames, scenes, the viewer's passes):
// whether it is lost and why, since when it owes an answer (it holds work and has said nothing since), and when it
// last heard from rank 0. No MPI. Who is lost may be read from another thread (the viewer's stats); the rest
// belongs to the thread that deals.

#include <atomic>
#include <chrono>
#include <memory>
#include <optional>
#include <vector>

namespace rayview::cluster {

class WorkerWatch {
 public:
  using Clock = std::chrono::steady_clock;
  // Why a worker is lost, as its dealer names it; kNotLost is never a reason.
  static constexpr int kNotLost = 0;
  static constexpr int kSilent = 1;

  // `lostBefore` (one per rank, may be shorter): the ranks lost in an earlier round, for kSilent.
  explicit WorkerWatch(int ranks, const std::vector<bool>& lostBefore = {});

  int ranks() const { return ranks_; }
  bool lost(int worker) const { return loss(worker) != kNotLost; }
  int loss(int worker) const { return loss_[static_cast<std::size_t>(worker)].load(); }
  std::vector<bool> lostRanks() const;
  // Marks `worker` lost for `why`: false when it was lost already (nothing to deal again). It owes nothing more.
  bool lose(int worker, int why = kSilent);

  // `worker` was dealt work at `now`: it owes an answer from then, unless it owed one already.
  void dealt(int worker, Clock::time_point now);
  // A word from `worker` (a result, a heartbeat): what it still holds (`holding`) is owed from now.
  void heard(int worker, bool holding);
  void sent(int worker) { lastSent_[static_cast<std::size_t>(worker)] = Clock::now(); }

  bool owes(int worker) const { return owedSince_[static_cast<std::size_t>(worker)].has_value(); }
  // Whether `worker` has owed an answer for longer than `patience` at `now`.
  bool owedLongerThan(int worker, Clock::time_point now, Clock::duration patience) const;
  // Whether rank 0 has sent `worker` nothing for longer than `quiet` at `now`.
  bool unsentLongerThan(int worker, Clock::time_point now, Clock::duration quiet) const {
    return now - lastSent_[static_cast<std::size_t>(worker)] > quiet;
  }

 private:
  int ranks_;
  std::unique_ptr<std::atomic<int>[]> loss_;
  std::vector<std::optional<Clock::time_point>> owedSince_;
  std::vector<Clock::time_point> lastSent_;
};

}  // namespace rayview::cluster
