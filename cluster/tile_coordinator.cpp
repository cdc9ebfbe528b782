#include <mpi.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <deque>
#include <string>
#include <thread>

#include "mpi_link.h"
#include "tile_exchange.h"
#include "tile_render.h"
#include "work_dealer.h"

namespace rayview::cluster {
namespace {

using Clock = std::chrono::steady_clock;

std::atomic<std::size_t> gPlaced{0};
std::atomic<std::size_t> gPlanned{0};
std::atomic<bool> gPeerLost{false};
std::atomic<std::size_t> gFramesWritten{0};
std::atomic<std::size_t> gFramesPlanned{0};

// Tiles a worker holds at once: one to render, one on its way, so that it never waits for the next. A whole frame
// fills a worker alone: a second one waiting behind it could leave the other ranks idle at the run's end, and a
// frame's round trip is small next to its render.
constexpr int kDepth = 2;
constexpr std::int32_t kStillWorking = -2;

double msBetween(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration<double, std::milli>(b - a).count();
}

class Coordinator final : public Dealing {
 public:
  Coordinator(const std::vector<WorkUnit>& units, int ranks, FrameAssembly& assembly, int round,
              const std::vector<bool>& lostBefore)
      : units_(units), assembly_(assembly), round_(round), tally_(static_cast<std::size_t>(ranks)),
        watch_(ranks, lostBefore), dealer_(units.size(), watch_, DealRules{kDepth}) {}

  ExchangeResult run(const TracerFor& tracerFor, ThreadPool& pool, std::vector<bool>& lostRanks) {
    if (ranks() == 1) {  // nobody to deal to: no coordinator polling beside the render
      renderOwnShare(tracerFor, pool);
      return {tally_, dealer_.pile().allFinished()};
    }
    std::thread local([&] { renderOwnShare(tracerFor, pool); });
    dealer_.run(*this);
    // A frame not written ends the job here, and the workers, a step behind rank 0, end without MPI_Finalize.
    if (assembly_.failed()) notePeerLost();
    // Lost ranks too: one only slow (starved of CPU) then ends cleanly; to a dead one the send never completes.
    for (int w = 1; w < ranks(); ++w) sendValue(w, peerLost() ? kNoMoreTilesRankLost : kNoMoreTiles);
    dealer_.pile().stop();  // a frame that could not be written ends the round with units left
    local.join();
    finishSends();
    lostRanks = watch_.lostRanks();
    for (int w = 1; w < ranks(); ++w) tally_[w].lost = lostRanks[w];
    return {tally_, dealer_.pile().allFinished()};
  }

  // What the dealer asks of tiles and whole frames:
  void send(int worker, std::size_t unit) override { sendValue(worker, static_cast<std::int32_t>(unit)); }
  bool receive() override;
  void nudge(int worker) override { sendValue(worker, kStillWorking); }
  void lost(int worker, int why, const std::vector<std::size_t>& units) override;
  Halt halt() override { return assembly_.failed() ? Halt::Now : Halt::No; }
  int weight(std::size_t unit) override { return units_[unit].whole ? kDepth : 1; }

 private:
  int ranks() const { return static_cast<int>(tally_.size()); }

  // Rank 0's own share, on a thread of its own: the main thread stays free to deal.
  void renderOwnShare(const TracerFor& tracerFor, ThreadPool& pool) {
    Image pixels;
    while (!assembly_.failed()) {
      const auto unit = dealer_.pile().takeOrWait(0);
      if (!unit) break;
      const WorkUnit& u = units_[*unit];
      const auto start = Clock::now();
      RayCounts rays;
      renderTile(tracerFor(u.frame), u.tile, pool, pixels, rays);
      count(tally_[0], *unit, msBetween(start, Clock::now()), rays);
      if (dealer_.finish(*unit)) place(*unit, pixels.rgb.data());
    }
  }

  void count(RankTally& tally, std::size_t unit, double busyMs, const RayCounts& rays) {
    tally.busyMs += busyMs;
    tally.rays += rays;
    ++(units_[unit].whole ? tally.frames : tally.tiles);
  }

  void place(std::size_t unit, const std::uint8_t* rgb) {
    gPlaced.fetch_add(1, std::memory_order_relaxed);
    assembly_.place(unit, rgb);
  }

  void sendValue(int worker, std::int32_t value) {
    outbox_.push_back({value, MPI_REQUEST_NULL});
    MPI_Isend(&outbox_.back().value, 1, MPI_INT32_T, worker, kTagTile, MPI_COMM_WORLD, &outbox_.back().request);
    // Completed sends leave the front; a send to a lost rank may never complete and is left alone.
    while (outbox_.size() > 64) {
      int done = 0;
      MPI_Test(&outbox_.front().request, &done, MPI_STATUS_IGNORE);
      if (!done) break;
      outbox_.pop_front();
    }
  }

  void takeResult(int worker) {
    TileResultHeader header;
    std::memcpy(&header, inbox_.data(), sizeof header);
    if (header.frame != round_) return;  // a late result of an earlier round
    const auto unit = static_cast<std::size_t>(header.tile);
    if (unit >= units_.size()) return;
    const Tile& t = units_[unit].tile;
    const std::size_t expected = sizeof header + static_cast<std::size_t>(t.x1 - t.x0) * (t.y1 - t.y0) * 3;
    if (inbox_.size() - 1 != expected) return;
    count(tally_[worker], unit, header.busyMs, RayCounts{header.camera, header.shadow, header.reflection});
    // A late result from a rank declared lost still counts, if no one else finished the unit first.
    if (dealer_.finish(unit)) place(unit, inbox_.data() + sizeof header);
    dealer_.release(worker, weight(unit));
  }

  // The last sends (the end of the tiles) are small and go eagerly; a lost rank's are not waited for.
  void finishSends() {
    const auto deadline = Clock::now() + std::chrono::seconds(1);
    while (!outbox_.empty() && Clock::now() < deadline) {
      int done = 0;
      MPI_Test(&outbox_.front().request, &done, MPI_STATUS_IGNORE);
      if (done) outbox_.pop_front();
      else std::this_thread::sleep_for(kProbePause);
    }
  }

  struct Outgoing {
    std::int32_t value;
    MPI_Request request;
  };

  const std::vector<WorkUnit>& units_;
  FrameAssembly& assembly_;
  int round_;
  std::vector<RankTally> tally_;
  WorkerWatch watch_;
  WorkDealer dealer_;
  std::deque<Outgoing> outbox_;  // a deque: each value stays where its send reads it
  std::vector<std::uint8_t> inbox_;
};

bool Coordinator::receive() {
  const std::optional<Arrival> arrival = receiveAny(inbox_, kLostAfter);
  if (!arrival) return false;
  const int worker = arrival->source;
  if (!arrival->whole) {
    dealer_.lose(*this, worker, WorkerWatch::kSilent);
    return true;
  }
  if (arrival->tag == kTagResult && arrival->bytes >= sizeof(TileResultHeader)) takeResult(worker);
  dealer_.heard(worker);
  return true;
}

// A worker silent while it held units (or mid-message) is lost: the job ends without MPI_Finalize, and its units
// go to the other ranks.
void Coordinator::lost(int worker, int /*why*/, const std::vector<std::size_t>& back) {
  notePeerLost();
  std::size_t frames = 0;
  for (std::size_t unit : back) frames += units_[unit].whole ? 1 : 0;
  const std::size_t tiles = back.size() - frames;
  auto counted = [](std::size_t n, const char* noun) { return std::to_string(n) + " " + noun + (n == 1 ? "" : "s"); };
  std::string what = frames > 0 ? counted(frames, "unfinished frame") : counted(tiles, "unfinished tile");
  if (frames > 0 && tiles > 0) what += " and " + counted(tiles, "tile");
  std::fprintf(stderr, "rayview: warning: rank %d fell silent for %.0f s holding %s; dealing %s to the other "
               "ranks\n", worker, std::chrono::duration<double>(kLostAfter).count(), what.c_str(),
               back.size() == 1 ? "it" : "them");
}

}  // namespace

ExchangeResult coordinateUnits(const std::vector<WorkUnit>& units, FrameAssembly& assembly, int ranks,
                               ThreadPool& pool, const TracerFor& tracerFor, int round, std::vector<bool>& lost) {
  gPlanned.store(units.size());
  gPlaced.store(0);
  Coordinator coordinator(units, ranks, assembly, round, lost);
  return coordinator.run(tracerFor, pool, lost);
}

std::size_t tilesPlaced() { return gPlaced.load(std::memory_order_relaxed); }
std::size_t tilesPlanned() { return gPlanned.load(std::memory_order_relaxed); }
void noteFrames(std::size_t written, std::size_t total) {
  gFramesWritten.store(written);
  gFramesPlanned.store(total);
}
std::size_t framesWritten() { return gFramesWritten.load(std::memory_order_relaxed); }
std::size_t framesPlanned() { return gFramesPlanned.load(std::memory_order_relaxed); }
bool peerLost() { return gPeerLost.load(); }
void notePeerLost() { gPeerLost.store(true); }

}  // namespace rayview::cluster
