#include <mpi.h>

#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <cstring>
#include <deque>
#include <mutex>
#include <optional>
#include <thread>

#include "mpi_link.h"
#include "mpi_outbox.h"
#include "rayview/exit_codes.h"
#include "tile_exchange.h"
#include "tile_render.h"

namespace rayview::cluster {
namespace {

using Clock = std::chrono::steady_clock;

// The unit being rendered, on a thread of its own, so that the main thread (the one that calls MPI) can keep
// rank 0 told that this rank is alive.
class TileRenderThread {
 public:
  TileRenderThread(const TracerFor& tracerFor, const std::vector<WorkUnit>& units, ThreadPool& pool, int round)
      : round_(round), thread_([this, &tracerFor, &units, &pool] { loop(tracerFor, units, pool); }) {}
  ~TileRenderThread() {
    {
      std::lock_guard lock(mutex_);
      quit_ = true;
    }
    changed_.notify_all();
    thread_.join();
  }

  void start(std::int32_t tile) {
    {
      std::lock_guard lock(mutex_);
      job_ = tile;
      done_ = false;
    }
    changed_.notify_all();
  }

  // Waits up to `wait` for the tile; true (with the message to send in `message`) when it is done.
  bool waitDone(std::chrono::milliseconds wait, std::vector<std::uint8_t>& message) {
    std::unique_lock lock(mutex_);
    if (!changed_.wait_for(lock, wait, [this] { return done_; })) return false;
    done_ = false;
    message.resize(sizeof header_ + pixels_.rgb.size());
    std::memcpy(message.data(), &header_, sizeof header_);
    std::memcpy(message.data() + sizeof header_, pixels_.rgb.data(), pixels_.rgb.size());
    return true;
  }

 private:
  void loop(const TracerFor& tracerFor, const std::vector<WorkUnit>& units, ThreadPool& pool) {
    std::unique_lock lock(mutex_);
    for (;;) {
      changed_.wait(lock, [this] { return quit_ || job_ >= 0; });
      if (quit_) return;
      const std::int32_t tile = job_;
      job_ = -1;
      lock.unlock();
      const auto start = Clock::now();
      RayCounts rays;
      const WorkUnit& unit = units.at(static_cast<std::size_t>(tile));
      renderTile(tracerFor(unit.frame), unit.tile, pool, pixels_, rays);
      const double ms = std::chrono::duration<double, std::milli>(Clock::now() - start).count();
      lock.lock();
      header_ = {tile, round_, ms, rays.camera, rays.shadow, rays.reflection};
      done_ = true;
      changed_.notify_all();
    }
  }

  std::mutex mutex_;
  std::condition_variable changed_;
  std::int32_t job_ = -1;
  bool done_ = false, quit_ = false;
  TileResultHeader header_;
  Image pixels_;
  int round_;
  std::thread thread_;  // last: starts once the members it uses exist
};


}  // namespace

int workOnUnits(const std::vector<WorkUnit>& units, const TracerFor& tracerFor, int rank, ThreadPool& pool, int round) {
  TileRenderThread renderer(tracerFor, units, pool, round);
  std::deque<std::int32_t> queue;
  bool ended = false, rendering = false;
  auto lastFromZero = Clock::now();
  std::vector<std::uint8_t> message;
  MPI_Request pending = MPI_REQUEST_NULL;
  for (;;) {
    MPI_Status status;
    // Nothing past the end of this round's units is read: what follows belongs to the next round.
    while (!ended && messageWaiting(0, kTagTile, status)) {
      std::int32_t value = 0;
      MPI_Recv(&value, 1, MPI_INT32_T, 0, kTagTile, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
      lastFromZero = Clock::now();
      if (value == kNoMoreTilesRankLost) notePeerLost();
      if (value == kNoMoreTiles || value == kNoMoreTilesRankLost) ended = true;
      else if (value >= 0 && static_cast<std::size_t>(value) < units.size()) queue.push_back(value);
    }
    if (rendering) {
      std::vector<std::uint8_t> finished;
      if (renderer.waitDone(std::chrono::duration_cast<std::chrono::milliseconds>(kAliveEvery), finished)) {
        rendering = false;
        // Rank 0's silence counts from here: while this rank rendered (a whole frame can take long) it owed nothing.
        lastFromZero = Clock::now();
        if (!queue.empty()) {  // the next tile starts before this one's pixels travel
          renderer.start(queue.front());
          queue.pop_front();
          rendering = true;
        }
        if (!completeWithin(pending, std::chrono::milliseconds(kRankZeroLostAfter))) break;
        message.swap(finished);
        MPI_Isend(message.data(), static_cast<int>(message.size()), MPI_BYTE, 0, kTagResult, MPI_COMM_WORLD, &pending);
      } else {
        MPI_Send(nullptr, 0, MPI_BYTE, 0, kTagAlive, MPI_COMM_WORLD);
      }
      continue;
    }
    if (!queue.empty()) {
      renderer.start(queue.front());
      queue.pop_front();
      rendering = true;
      continue;
    }
    if (ended) return completeWithin(pending, std::chrono::milliseconds(kRankZeroLostAfter)) ? kExitOk : kExitIoFailure;
    if (Clock::now() - lastFromZero > kRankZeroLostAfter) break;
    std::this_thread::sleep_for(kProbePause);
  }
  notePeerLost();
  std::fprintf(stderr, "rayview: rank %d: no word from rank 0 for %.0f s; stopping\n", rank,
               std::chrono::duration<double>(kRankZeroLostAfter).count());
  return kExitIoFailure;
}

}  // namespace rayview::cluster
