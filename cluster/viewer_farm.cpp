#include "viewer_farm.h"

#include <mpi.h>

#include <algorithm>
#include <chrono>
#include <climits>
#include <cstdio>
#include <cstring>
#include <deque>
#include <mutex>
#include <optional>
#include <thread>

#include "mpi_link.h"
#include "rayview/grid_render.h"
#include "tile_exchange.h"
#include "tile_plan.h"
#include "view_codec.h"
#include "view_messages.h"
#include "work_dealer.h"

namespace rayview::cluster {
namespace {

using Clock = std::chrono::steady_clock;

// Tiles a worker holds at once (one to trace, one on its way), rank 0's own thread taking its own; no nudges (a
// worker waits for rank 0 however long the window is idle). A worker holding tiles and silent kLostAfter is left
// out, its tiles dealt to the others: it says it is alive every kAliveEvery while it builds or traces, so this is
// a rank that stopped, not a slow one.
constexpr DealRules kPassRules{2, false, false, kLostAfter};
// A tile owed this long at the end of a pass is dealt again to a free rank (see Pass::patience).
constexpr auto kLatePatience = std::chrono::milliseconds(40);

template <class T>
std::vector<std::uint8_t> bytesOf(const T& value) {
  std::vector<std::uint8_t> bytes(sizeof value);
  std::memcpy(bytes.data(), &value, sizeof value);
  return bytes;
}

}  // namespace

// One pass: its tiles dealt to the workers and to rank 0's own thread, their pixels handed to the sink as they come.
class ViewerFarm::Pass final : public Dealing {
 public:
  Pass(ViewerFarm& farm, const PixelSource& source, const FarmPass& pass, const FarmSink& sink,
       const std::function<bool()>& stopped, RayCounts& rays)
      : farm_(farm), source_(source), pass_(pass), sink_(sink), stopped_(stopped), rays_(rays),
        tiles_(clusterTiles((source.width() + pass.stride - 1) / pass.stride,
                            (source.height() + pass.stride - 1) / pass.stride, farm.ranks_)),
        dealer_(tiles_.size(), farm.watch_, kPassRules), dealtAt_(tiles_.size()) {}

  bool run() {
    // What the workers sent while no pass listened (late results, heartbeats) speaks for them before any silence is
    // judged: a rank idle between passes is silent only from rank 0's side.
    while (receiveOne()) {
    }
    std::thread local([this] { traceOwnShare(); });
    const bool complete = dealer_.run(*this);
    dealer_.pile().stop();
    local.join();
    takeLocal();
    return complete;
  }

  // What the dealer asks of a pass's tiles:
  void send(int worker, std::size_t tile) override {
    dealtAt_[tile] = Clock::now();
    const Tile& t = tiles_[tile];
    const ViewTileRequest request{farm_.passSerial_, pass_.generation, static_cast<std::int32_t>(tile),
                                  pass_.stride, pass_.skipStride, pass_.sample, t.x0, t.y0, t.x1, t.y1};
    farm_.sendTo(worker, kTagViewTile, bytesOf(request));
  }
  bool receive() override {  // both, every time: no short-circuit
    const bool own = takeLocal();
    const bool received = receiveOne();
    return own || received;
  }
  void lost(int worker, int why, const std::vector<std::size_t>& /*tiles*/) override {
    if (why == static_cast<int>(Loss::Silent))
      std::fprintf(stderr, "rayview: warning: rank %d fell silent; the other ranks go on without it\n", worker);
  }
  Halt halt() override { return stopped_() ? Halt::Now : Halt::No; }
  // How long a rank may owe a tile before it counts as late: twice the slowest tile of this pass so far, and never
  // less than kLatePatience (a tile's round trip on a busy machine). A rank that is only slow may still win.
  std::optional<Clock::duration> patience() override {
    return std::max<Clock::duration>(kLatePatience, 2 * slowestTile_);
  }

 private:
  struct LocalTile {
    std::size_t tile;
    std::vector<PixelXY> pixels;
    std::vector<Color> colors;
    RayCounts rays;
    std::uint64_t busyMicroseconds = 0;
  };

  // Rank 0's own share, on a thread of its own: the calling thread stays free to deal and receive.
  void traceOwnShare() {
    while (const auto tile = dealer_.pile().takeOrWait(0)) {
      LocalTile done{*tile, {}, {}, {}, 0};
      gridTilePixels(tiles_[*tile], pass_.stride, pass_.skipStride, done.pixels);
      const auto start = Clock::now();
      traceColors(farmTrace(source_, pass_.sample), done.pixels, farm_.pool_, done.colors, done.rays);
      done.busyMicroseconds =
          static_cast<std::uint64_t>(std::chrono::duration<double, std::micro>(Clock::now() - start).count());
      std::lock_guard lock(localMutex_);
      local_.push_back(std::move(done));
    }
  }

  bool takeLocal() {
    std::deque<LocalTile> done;
    {
      std::lock_guard lock(localMutex_);
      done.swap(local_);
    }
    for (LocalTile& t : done) {
      rays_ += t.rays;
      if (!dealer_.finish(t.tile)) continue;
      ++farm_.tilesTraced_[0];
      farm_.busyMicroseconds_[0] += t.busyMicroseconds;
      sink_(t.pixels.data(), t.colors.data(), static_cast<int>(t.pixels.size()));
    }
    return !done.empty();
  }

  bool receiveOne() {
    // Never a blocking receive: a worker that died mid-message would hold the window's renderer for ever.
    const std::optional<Arrival> arrival = receiveAny(inbox_, kLostAfter);
    if (!arrival) return false;
    const int worker = arrival->source;
    if (!arrival->whole) {
      std::fprintf(stderr, "rayview: warning: rank %d fell silent mid-message; the other ranks go on without it\n",
                   worker);
      dealer_.lose(*this, worker, static_cast<int>(Loss::SilentMidMessage));
      return true;
    }
    if (arrival->tag == kTagViewProblem) {
      std::fprintf(stderr, "rayview: error: rank %d cannot trace: %.*s; the other ranks go on without it\n", worker,
                   static_cast<int>(arrival->bytes), reinterpret_cast<const char*>(inbox_.data()));
      dealer_.lose(*this, worker, static_cast<int>(Loss::CannotTrace));
    } else if (arrival->tag == kTagViewResult && arrival->bytes >= sizeof(ViewTileResultHeader)) {
      takeResult(worker, arrival->bytes);
    }
    // Any word from it (a result, a heartbeat) says it is alive: what it still holds is owed from now on.
    dealer_.heard(worker);
    return true;
  }

  void takeResult(int worker, std::size_t bytes) {
    ViewTileResultHeader header;
    std::memcpy(&header, inbox_.data(), sizeof header);
    if (header.pass != farm_.passSerial_) return;  // a late result of an earlier pass
    dealer_.release(worker);
    const auto tile = static_cast<std::size_t>(header.tile);
    if (tile >= tiles_.size()) return;
    gridTilePixels(tiles_[tile], pass_.stride, pass_.skipStride, pixels_);
    const std::size_t expected = sizeof header + pixels_.size() * sizeof(Color);
    const bool whole = bytes == expected && static_cast<std::size_t>(header.pixels) == pixels_.size();
    if (whole) slowestTile_ = std::max(slowestTile_, Clock::now() - dealtAt_[tile]);
    // The first result of a tile dealt twice (to a late rank, then to a free one) gives its pixels.
    if (!whole || !dealer_.finish(tile)) return;
    colors_.resize(pixels_.size());
    // A tile may hold no pixel of the pass (all on the coarser grid), and memcpy must not see a null pointer.
    if (!pixels_.empty()) std::memcpy(colors_.data(), inbox_.data() + sizeof header, pixels_.size() * sizeof(Color));
    rays_ += RayCounts{header.camera, header.shadow, header.reflection};
    ++farm_.tilesTraced_[worker];
    farm_.busyMicroseconds_[worker] += static_cast<std::uint64_t>(header.busyMs * 1000.0);
    sink_(pixels_.data(), colors_.data(), static_cast<int>(pixels_.size()));
  }

  using Loss = ViewerFarm::Loss;
  ViewerFarm& farm_;
  const PixelSource& source_;
  FarmPass pass_;
  const FarmSink& sink_;
  const std::function<bool()>& stopped_;
  RayCounts& rays_;
  std::vector<Tile> tiles_;
  WorkDealer dealer_;
  std::vector<Clock::time_point> dealtAt_;  // per tile: when it was last dealt
  Clock::duration slowestTile_{};  // the longest a tile of this pass took from dealt to its result
  std::mutex localMutex_;
  std::deque<LocalTile> local_;
  std::vector<std::uint8_t> inbox_;
  std::vector<PixelXY> pixels_;
  std::vector<Color> colors_;
};

ViewerFarm::ViewerFarm(int ranks, int threads)
    : ranks_(std::max(ranks, 1)), pool_(threads),
      watch_(ranks_),
      tilesTraced_(std::make_unique<std::atomic<std::size_t>[]>(static_cast<std::size_t>(ranks_))),
      busyMicroseconds_(std::make_unique<std::atomic<std::uint64_t>[]>(static_cast<std::size_t>(ranks_))) {}

std::string ViewerFarm::describe() const {
  int working = 0;
  for (int r = 0; r < ranks_; ++r) working += lost(r) ? 0 : 1;
  // A lost rank is counted out of the total, and its time is not shown as work going on.
  std::string text = (working == ranks_ ? std::to_string(ranks_) : std::to_string(working) + " of " + std::to_string(ranks_)) +
                     " ranks, busy";
  for (int r = 0; r < ranks_; ++r)
    text += (r == 0 ? " " : " / ") + (lost(r) ? std::string("lost") : std::to_string(busyMicroseconds_[r].load() / 1000)) +
            (r + 1 < ranks_ ? "" : " ms");
  return text;
}

namespace {

const char* lossText(ViewerFarm::Loss why) {
  switch (why) {
    case ViewerFarm::Loss::Silent: return "fell silent (died or stopped)";
    case ViewerFarm::Loss::SilentMidMessage: return "fell silent mid-message";
    case ViewerFarm::Loss::CannotTrace: return "cannot trace the scene";
    case ViewerFarm::Loss::SceneTooLarge: return "left out: the scene is too large to send";
    case ViewerFarm::Loss::None: break;
  }
  return "";
}

}  // namespace

std::vector<std::string> ViewerFarm::lostRanks() const {
  std::vector<std::string> lostOnes;
  for (int r = 1; r < ranks_; ++r)
    if (lost(r)) lostOnes.push_back("rank " + std::to_string(r) + ": " + lossText(loss(r)));
  return lostOnes;
}

ViewerFarm::~ViewerFarm() = default;

bool ViewerFarm::accepts(const PixelSource& source) const {
  return !ended_ && dynamic_cast<const TracedImage*>(&source) != nullptr;
}

bool ViewerFarm::renderPass(const PixelSource& source, const FarmPass& pass, const FarmSink& sink,
                            const std::function<bool()>& stopped, RayCounts& rays) {
  ship(dynamic_cast<const TracedImage&>(source), pass.generation);
  ++passSerial_;
  Pass running(*this, source, pass, sink, stopped, rays);
  const bool complete = running.run();
  outbox_.reap();
  return complete;
}

// The geometry when it is new to the workers (a scene opened, another traversal), then this generation's parameters.
void ViewerFarm::ship(const TracedImage& image, std::uint64_t generation) {
  if (image.geometry() != shippedGeometry_) {
    shippedGeometry_ = image.geometry();
    ++geometrySerial_;
    const PreparedGeometry& geometry = *shippedGeometry_;
    Bytes bytes = bytesOf(geometrySerial_);
    const Bytes body =
        encodeGeometry(*geometry.source, geometry.shading.origin, geometry.accel->kind(), image.parameters().get());
    bytes.insert(bytes.end(), body.begin(), body.end());
    sendToAll(kTagViewGeometry, std::move(bytes));
  }
  if (generation == shippedGeneration_) return;
  shippedGeneration_ = generation;
  Bytes bytes = bytesOf(ViewSnapshotHeader{generation, geometrySerial_});
  const Bytes body = encodeSnapshot(*image.parameters(), image.settings());
  bytes.insert(bytes.end(), body.begin(), body.end());
  sendToAll(kTagViewSnapshot, std::move(bytes));
}

void ViewerFarm::sendTo(int worker, int tag, std::vector<std::uint8_t> bytes) {
  outbox_.send(worker, tag, std::move(bytes));
}

// One buffer for every worker not left out (a scene's geometry is sent once, not copied per rank).
void ViewerFarm::sendToAll(int tag, std::vector<std::uint8_t> bytes) {
  if (bytes.size() > static_cast<std::size_t>(INT_MAX)) {
    std::fprintf(stderr, "rayview: error: the scene is too large to send to the other ranks (over 2 GB); this window "
                 "traces it alone\n");
    for (int w = 1; w < ranks_; ++w) watch_.lose(w, static_cast<int>(Loss::SceneTooLarge));
    return;
  }
  const auto shared = std::make_shared<const std::vector<std::uint8_t>>(std::move(bytes));
  for (int w = 1; w < ranks_; ++w)
    if (!lost(w)) outbox_.sendPart(w, tag, shared, 0, shared->size());
}

// A rank that still owes tiles when the window closes may have died between passes: any word from it says it is
// alive (it will say goodbye once its tile is done); silent until kLostAfter from when it began to owe, it is lost,
// and the others are told to end without it (MPI_Finalize would wait for it for ever).
void ViewerFarm::settleOwed() {
  std::vector<std::uint8_t> inbox;
  for (;;) {
    // Everything that arrived since the last pass is read before any rank is judged silent: nobody listened then.
    while (const std::optional<Arrival> arrival = receiveAny(inbox, std::chrono::milliseconds(kLostAfter))) {
      if (arrival->whole) watch_.heard(arrival->source, false);
      else watch_.lose(arrival->source, static_cast<int>(Loss::SilentMidMessage));
    }
    const auto now = Clock::now();
    bool owing = false;
    for (int w = 1; w < ranks_; ++w) {
      if (lost(w) || !watch_.owes(w)) continue;
      if (watch_.owedLongerThan(w, now, kLostAfter)) {
        std::fprintf(stderr, "rayview: warning: rank %d fell silent; the other ranks end without it\n", w);
        watch_.lose(w, static_cast<int>(Loss::Silent));
      } else {
        owing = true;
      }
    }
    if (!owing) return;
    std::this_thread::sleep_for(kLongestProbePause);
  }
}

void ViewerFarm::shutdown() {
  if (ended_) return;
  ended_ = true;
  settleOwed();
  // With a rank lost, MPI_Finalize would wait for it for ever: the others are told to end without it.
  std::vector<bool> gone(static_cast<std::size_t>(ranks_), false);
  for (int r = 0; r < ranks_; ++r) gone[r] = lost(r);
  const bool anyLost = std::find(gone.begin(), gone.end(), true) != gone.end();
  if (anyLost) notePeerLost();
  // A rank left out only for its silence may still be there and hear it; a dead one's send is not waited for.
  for (int w = 1; w < ranks_; ++w) sendTo(w, kTagViewQuit, {static_cast<std::uint8_t>(anyLost ? 1 : 0)});
  // Every worker's last message is its goodbye: what it sent before (late results) is read and dropped.
  int waiting = static_cast<int>(std::count(gone.begin() + 1, gone.end(), false));
  std::vector<std::uint8_t> inbox;
  const auto deadline = Clock::now() + std::chrono::seconds(5);
  while (waiting > 0 && Clock::now() < deadline) {
    MPI_Status status;
    if (!messageWaiting(MPI_ANY_SOURCE, MPI_ANY_TAG, status)) {
      outbox_.reap();
      std::this_thread::sleep_for(kLongestProbePause);
      continue;
    }
    int bytes = 0;
    MPI_Get_count(&status, MPI_BYTE, &bytes);
    inbox.resize(static_cast<std::size_t>(bytes) + 1);
    MPI_Recv(inbox.data(), bytes, MPI_BYTE, status.MPI_SOURCE, status.MPI_TAG, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    if (status.MPI_TAG == kTagViewBye && !gone[status.MPI_SOURCE]) {
      gone[status.MPI_SOURCE] = true;
      --waiting;
    }
  }
  outbox_.drain(std::chrono::seconds(5));
  if (waiting > 0) notePeerLost();
  // Who traced what, for the user deciding how many ranks are worth it (and for the tests). A lost rank is said to be
  // lost, not listed as working: what it traced before counts for nothing now.
  std::printf("tiles traced:");
  for (int r = 0; r < ranks_; ++r) {
    if (lost(r)) std::printf(" rank %d lost: %s", r, lossText(loss(r)));
    else std::printf(" rank %d %zu (busy %.0f ms)", r, tilesTraced_[r].load(),
                     static_cast<double>(busyMicroseconds_[r].load()) / 1000.0);
    std::printf("%s", r + 1 < ranks_ ? "," : "\n");
  }
  std::fflush(stdout);
}

std::shared_ptr<ViewerPassFarm> makeViewerFarm(int ranks, int threads) {
  return std::make_shared<ViewerFarm>(ranks, threads);
}

}  // namespace rayview::cluster
