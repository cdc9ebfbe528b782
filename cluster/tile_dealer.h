#pragma once
// Who renders which tile of a distributed render: tiles are taken one at a time by whichever rank asks (rank
// 0's own render thread and the coordinator, for the other ranks, at once), and a lost rank's tiles go back to
// the front of the pile for the survivors. Thread-safe; no MPI.

#include <condition_variable>
#include <cstddef>
#include <deque>
#include <mutex>
#include <optional>
#include <vector>

namespace rayview::cluster {

class TileDealer {
 public:
  explicit TileDealer(std::size_t tiles);

  // The next tile nobody holds, now held by `rank`; nullopt when none is left to deal.
  std::optional<std::size_t> take(int rank);
  // The same, waiting while tiles are held by others that may yet come back; nullopt once all are finished
  // or `stopped()` was called.
  std::optional<std::size_t> takeOrWait(int rank);
  // `rank` finished `tile`: true the first time the tile is finished (its pixels are to be kept).
  bool finish(std::size_t tile, int rank);
  // `rank` is lost: the tiles it holds and has not finished go back to the front of the pile; returns them.
  std::vector<std::size_t> reclaim(int rank);
  // The tile take would give next, left in the pile; nullopt when none is left to deal.
  std::optional<std::size_t> next() const;
  // The tiles `rank` holds and has not finished.
  std::vector<std::size_t> heldBy(int rank) const;
  // Wakes every takeOrWait for good.
  void stop();

  std::size_t total() const { return holder_.size(); }
  std::size_t finished() const;
  bool allFinished() const { return finished() == total(); }

 private:
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
