#include "scene_batch.h"

#include <mpi.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <deque>
#include <future>
#include <memory>
#include <string>
#include <thread>
#include <utility>

#include "rayview/exit_codes.h"
#include "mpi_link.h"
#include "mpi_outbox.h"
#include "scene_distribution.h"
#include "scene_hash.h"
#include "scene_render_thread.h"
#include "work_dealer.h"

namespace rayview::cluster {
namespace {

using Clock = std::chrono::steady_clock;

// MPI counts are ints: a scene order goes in pieces.
constexpr std::size_t kPiece = std::size_t{1} << 30;

// A scene between its load on rank 0 and its last frame written.
struct SceneInFlight {
  std::shared_ptr<const Scene> scene;
  RenderSettings settings;
  std::uint64_t hash = 0;  // computed when first sent to a worker
  bool hashed = false;
  std::vector<bool> written;  // per frame of the run
};

struct SceneLoad {
  int code = kExitOk;
  std::string message;  // the located load error
  std::shared_ptr<const Scene> scene;
  RenderSettings settings;
};

// A scene of the batch loaded as the single process loads it (its warnings printed), the knobs applied.
SceneLoad loadScene(const RenderJob& job) {
  SceneLoad load;
  LoadedScene loaded;
  load.code = loadSceneOnRankZero(job, loaded, load.message);
  if (load.code != kExitOk) return load;
  if (!job.quiet)
    for (const Diagnostic& warning : loaded.warnings) std::fprintf(stderr, "%s\n", warning.format().c_str());
  applyKnobs(job.knobs, {&loaded.scene.parameters(), &load.settings});
  load.scene = std::make_shared<const Scene>(std::move(loaded.scene));
  return load;
}

// A rank holds one scene at a time: its frames come back one by one, and it is idle again after the last.
constexpr DealRules kSceneRules{1, true};

class SceneCoordinator final : public Dealing {
 public:
  SceneCoordinator(const RenderJob& job, const std::vector<FrameJob>& frames, const std::vector<SceneRun>& runs,
                   ThreadPool& pool, FrameProgress& progress, std::vector<RankTally>& tally)
      : job_(job), frames_(frames), runs_(runs), progress_(progress), tally_(tally), scenes_(runs.size()),
        holding_(tally.size()), watch_(static_cast<int>(tally.size())), dealer_(runs.size(), watch_, kSceneRules),
        own_(pool) {}

  int run() {
    dealer_.run(*this);
    const std::int32_t end[2] = {code_, peerLost() ? 1 : 0};
    for (int w = 1; w < ranks(); ++w)
      post(w, kTagSceneEnd, Bytes(reinterpret_cast<const std::uint8_t*>(end),
                                  reinterpret_cast<const std::uint8_t*>(end) + sizeof end));
    // The end is small and goes eagerly; a lost rank's is not waited for.
    outbox_.drain(std::chrono::seconds(1));
    for (int w = 1; w < ranks(); ++w) tally_[w].lost = watch_.lost(w);
    if (!message_.empty()) std::fprintf(stderr, "%s\n", message_.c_str());
    return code_;
  }

  // What the dealer asks of scenes: each is sent whole to one rank (rank 0's own render thread last), in the batch's
  // order, once rank 0 has loaded it.
  void send(int rank, std::size_t run) override {
    holding_[static_cast<std::size_t>(rank)] = {run, framesOf(run)};
    if (rank == 0) renderOwn(run);
    else sendScene(rank, run);
  }
  bool receive() override {  // both, every time: no short-circuit
    const bool own = takeOwnResults();
    const bool received = receiveOne();
    return own || received;
  }
  void nudge(int worker) override { post(worker, kTagNudge, {}); }
  void lost(int worker, int why, const std::vector<std::size_t>& runs) override;
  Halt halt() override { return stopped_ ? Halt::AfterHeld : Halt::No; }
  bool ready(std::size_t run) override;
  void tick() override {
    if (!stopped_) loadAhead();
    outbox_.reap();
  }

 private:
  // The scene a rank renders and how many of its frames are still to come back.
  struct Holding {
    std::size_t run = 0;
    std::size_t framesLeft = 0;
  };

  int ranks() const { return static_cast<int>(tally_.size()); }
  std::size_t framesOf(std::size_t run) const { return runs_[run].end - runs_[run].first; }
  const FrameJob& frameOf(std::size_t run, std::size_t k) const { return frames_[runs_[run].first + k]; }

  void stop(int code, std::string message) {
    if (stopped_) return;
    stopped_ = true;
    code_ = code;
    message_ = std::move(message);
  }

  // The next scene of the pile, loaded while the ranks render, so that the next idle rank does not wait for its
  // parse.
  void loadAhead() {
    if (const auto next = dealer_.pile().next()) ready(*next);
  }

  // The held scene of `rank` is no more: it is idle.
  void idle(int rank) {
    holding_[static_cast<std::size_t>(rank)] = {};
    dealer_.releaseAll(rank);
  }

  std::vector<std::int32_t> frameList(std::size_t run) const {
    std::vector<std::int32_t> list;
    for (std::size_t k = 0; k < framesOf(run); ++k) list.insert(list.end(), {frameOf(run, k).frame, frameOf(run, k).frames});
    return list;
  }

  void renderOwn(std::size_t run) {
    const SceneToRender given{scenes_[run].scene, scenes_[run].settings};
    own_.start({static_cast<std::int32_t>(run), [given] { return given; }, frameList(run), false});
  }

  // The scene as loaded, knobs applied, to `worker` alone: the order's size, then the order in pieces.
  void sendScene(int worker, std::size_t run) {
    SceneInFlight& scene = scenes_[run];
    if (!scene.hashed) scene.hash = sceneHash(*scene.scene), scene.hashed = true;
    SceneOrder order;
    order.run = static_cast<std::int32_t>(run);
    order.scenePath = frameOf(run, 0).scenePath;
    order.frames = frameList(run);
    order.geometry = encodeGeometry(scene.scene->geometry(), scene.scene->camera.position, scene.settings.accel);
    order.parameters = encodeSnapshot(scene.scene->parameters(), scene.settings);
    auto bytes = std::make_shared<const Bytes>(encodeSceneOrder(order));
    const auto size = static_cast<std::int64_t>(bytes->size());
    post(worker, kTagScene, Bytes(reinterpret_cast<const std::uint8_t*>(&size),
                                  reinterpret_cast<const std::uint8_t*>(&size) + sizeof size));
    for (std::size_t at = 0; at < bytes->size(); at += kPiece)
      outbox_.sendPart(worker, kTagSceneBytes, bytes, at, std::min(kPiece, bytes->size() - at));
  }

  void post(int worker, int tag, Bytes bytes) { outbox_.send(worker, tag, std::move(bytes)); }

  bool takeOwnResults() {
    bool any = false;
    while (auto done = own_.next(std::chrono::milliseconds(0))) {
      any = true;
      if (!done->error.empty()) {
        stop(kExitBadInput, "rayview: rank 0: " + done->error);
        idle(0);
        continue;
      }
      frameDone(0, *done, done->image.rgb.data(), done->image.rgb.size());
    }
    return any;
  }

  bool receiveOne() {
    const std::optional<Arrival> arrival = receiveAny(inbox_, kLostAfter);
    if (!arrival) return false;
    const int worker = arrival->source;
    if (!arrival->whole) {
      dealer_.lose(*this, worker, WorkerWatch::kSilent);
      return true;
    }
    if (arrival->tag == kTagSceneResult && arrival->bytes >= sizeof(SceneResultHeader)) {
      SceneResultHeader header;
      std::memcpy(&header, inbox_.data(), sizeof header);
      SceneFrameDone done{header.run, header.frame, Image(), header.busyMs,
                          RayCounts{header.camera, header.shadow, header.reflection}, header.hash, {}};
      frameDone(worker, done, inbox_.data() + sizeof header, arrival->bytes - sizeof header);
    } else if (arrival->tag == kTagLoadError) {
      stop(kExitBadInput, "rayview: rank " + std::to_string(worker) + ": " +
                              std::string(reinterpret_cast<const char*>(inbox_.data()), arrival->bytes));
      if (!watch_.lost(worker)) idle(worker);
    }
    dealer_.heard(worker);  // after what it said: a rank idle again owes nothing
    return true;
  }

  // A frame from `rank` (its pixels `rgb`): written unless another rank wrote it first; the rank is idle again after
  // its run's last frame.
  void frameDone(int rank, const SceneFrameDone& done, const std::uint8_t* rgb, std::size_t bytes) {
    const auto run = static_cast<std::size_t>(done.run);
    if (run >= runs_.size() || done.frame < 0 || static_cast<std::size_t>(done.frame) >= framesOf(run)) return;
    RankTally& tally = tally_[rank];
    tally.busyMs += done.busyMs;
    tally.rays += done.rays;
    ++tally.frames;
    Holding& holding = holding_[static_cast<std::size_t>(rank)];
    if (holding.framesLeft > 0 && holding.run == run && --holding.framesLeft == 0) idle(rank), ++tally.scenes;
    SceneInFlight& scene = scenes_[run];
    if (!scene.scene || scene.written[static_cast<std::size_t>(done.frame)]) return;  // a late copy
    if (rank != 0 && done.hash != scene.hash) {
      char text[200];
      std::snprintf(text, sizeof text, "rayview: error: rank %d loaded a scene that differs from rank 0's (hash "
                    "%016llx, not %016llx)", rank, static_cast<unsigned long long>(done.hash),
                    static_cast<unsigned long long>(scene.hash));
      return stop(kExitIoFailure, text);
    }
    writeFrame(run, static_cast<std::size_t>(done.frame), rgb, bytes, rank);
  }

  void writeFrame(std::size_t run, std::size_t k, const std::uint8_t* rgb, std::size_t bytes, int rank) {
    SceneInFlight& scene = scenes_[run];
    const Camera& camera = scene.scene->camera;  // a turntable's frames keep the lens: the same size
    Image image(camera.width, camera.height);
    if (bytes != image.rgb.size())
      return stop(kExitIoFailure, "rayview: error: rank " + std::to_string(rank) + " sent a frame of the wrong size");
    std::memcpy(image.rgb.data(), rgb, bytes);
    const FrameJob& frame = frameOf(run, k);
    if (const int code = writeFrameFile(frame.output, std::move(image)); code != kExitOk) return stop(code, {});
    scene.written[k] = true;
    progress_.frameWritten(frame.output, job_.quiet);
    noteFrames(progress_.written(), frames_.size());
    if (std::find(scene.written.begin(), scene.written.end(), false) != scene.written.end()) return;
    dealer_.finish(run);
    scene = SceneInFlight();  // rank 0 holds only the scenes in flight
  }

  const RenderJob& job_;
  const std::vector<FrameJob>& frames_;
  const std::vector<SceneRun>& runs_;
  FrameProgress& progress_;
  std::vector<RankTally>& tally_;
  std::vector<SceneInFlight> scenes_;
  std::vector<Holding> holding_;  // per rank
  WorkerWatch watch_;
  WorkDealer dealer_;  // the scenes, dealt in order; a lost rank's back to the front
  Outbox outbox_{[this](int rank) { return watch_.lost(rank); }};
  Bytes inbox_;
  std::future<SceneLoad> loading_;  // the scene being loaded, at most one
  std::size_t loadingRun_ = 0;
  bool stopped_ = false;
  int code_ = kExitOk;
  std::string message_;
  SceneRenderThread own_;  // last: its thread ends before the members it reports to
};

// A rank silent while it held a scene (or mid-message) is lost: the job ends without MPI_Finalize, and its scene
// goes back to the pile.
void SceneCoordinator::lost(int worker, int /*why*/, const std::vector<std::size_t>& /*runs*/) {
  notePeerLost();
  const Holding holding = std::exchange(holding_[static_cast<std::size_t>(worker)], {});
  if (holding.framesLeft == 0) return;
  std::fprintf(stderr, "rayview: warning: rank %d fell silent for %.0f s holding the scene %s; dealing it to the "
               "other ranks\n", worker, std::chrono::duration<double>(kLostAfter).count(),
               frameOf(holding.run, 0).scenePath.c_str());
}

// Whether `run` is loaded; if not, its load is started (one at a time, on a thread of its own, so that this
// thread keeps answering the ranks however long a parse takes). A load that failed stops the batch.
bool SceneCoordinator::ready(std::size_t run) {
  SceneInFlight& scene = scenes_[run];
  if (scene.scene) return true;
  if (!loading_.valid()) {
    const RenderJob sceneJob = jobForFrame(job_, frameOf(run, 0));
    loadingRun_ = run;
    loading_ = std::async(std::launch::async, [sceneJob] { return loadScene(sceneJob); });
    return false;
  }
  if (loadingRun_ != run || loading_.wait_for(std::chrono::seconds(0)) != std::future_status::ready) return false;
  SceneLoad load = loading_.get();
  if (load.code != kExitOk) {
    stop(load.code, load.message);
    return false;
  }
  scene.scene = std::move(load.scene);
  scene.settings = load.settings;
  scene.written.assign(framesOf(run), false);
  return true;
}

}  // namespace

int dealScenes(const RenderJob& job, const std::vector<FrameJob>& frames, const std::vector<SceneRun>& runs,
               ThreadPool& pool, FrameProgress& progress, std::vector<RankTally>& tally) {
  SceneCoordinator coordinator(job, frames, runs, pool, progress, tally);
  return coordinator.run();
}

}  // namespace rayview::cluster
