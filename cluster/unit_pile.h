#pragma once
// Who works on which unit of a dealt job (a tile, a whole frame, a scene, a tile of a viewer's pass): units are
// taken one at a time by whichever rank asks (rank 0's own render thread and the dealer, for the other ranks, at
// once), and a lost rank's units go back to the front of the pile for the survivors. Thread-safe; no MPI.

#include <condition_variable>
#include <cstddef>
#include <deque>
#include <mutex>
#include <optional>
#include <vector>

namespace rayview::cluster {

class UnitPile {
 public:
  explicit UnitPile(std::size_t units);

  // The next unit nobody holds, now held by `rank`; nullopt when none is left to deal.
  std::optional<std::size_t> take(int rank);
  // The same, waiting while units are held by others that may yet come back; nullopt once all are finished
  // or `stopped()` was called.
  std::optional<std::size_t> takeOrWait(int rank);
  // `unit` is finished: true the first time (its result is to be kept; a later copy is not).
  bool finish(std::size_t unit);
  // `rank` is lost, or late: the units it holds and has not finished go back to the front of the pile; returns them.
  std::vector<std::size_t> reclaim(int rank);
  // The unit take would give next, left in the pile; nullopt when none is left to deal.
  std::optional<std::size_t> next() const;
  // The units `rank` holds and has not finished.
  std::vector<std::size_t> heldBy(int rank) const;
  // Wakes every takeOrWait for good.
  void stop();

  std::size_t total() const { return holder_.size(); }
  std::size_t finished() const;
  bool allFinished() const { return finished() == total(); }

 private:
  std::optional<std::size_t> takeLocked(int rank);

  static constexpr int kNobody = -1;
  mutable std::mutex mutex_;
  std::condition_variable changed_;
  std::deque<std::size_t> pile_;
  std::vector<int> holder_;
  std::vector<bool> done_;
  std::size_t finished_ = 0;
  bool stopped_ = false;
};

}  // namespace rayview::cluster
