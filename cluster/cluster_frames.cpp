#include <mpi.h>

#include <algorithm>
#include <cstdio>
#include <memory>
#include <string>

#include "cluster_runs.h"
#include "rayview/exit_codes.h"
#include "mpi_link.h"
#include "rayview/frame_scene.h"
#include "frame_units.h"
#include "rayview/thread_pool.h"
#include "scene_batch.h"
#include "scene_distribution.h"
#include "tile_exchange.h"

namespace rayview::cluster {
namespace {

// Rank 0's frames to every rank, as text: scene, camera, frame, frames, output, one field a line.
std::vector<FrameJob> broadcastFrames(int rank, const std::vector<FrameJob>& frames, int& code) {
  std::string text;
  if (rank == 0)
    for (const FrameJob& f : frames)
      text += f.scenePath + '\n' + std::to_string(f.camera) + '\n' + std::to_string(f.frame) + '\n' + std::to_string(f.frames) + '\n' + f.output.string() + '\n';
  std::int64_t header[2] = {code, static_cast<std::int64_t>(text.size())};
  broadcastGently(header, 2, MPI_INT64_T);
  code = static_cast<int>(header[0]);
  if (code != kExitOk) return {};
  text.resize(static_cast<std::size_t>(header[1]));
  broadcastGently(text.data(), static_cast<int>(text.size()), MPI_CHAR);
  std::vector<FrameJob> all;
  std::size_t at = 0;
  auto line = [&] {
    const std::size_t end = text.find('\n', at);
    std::string field = text.substr(at, end - at);
    at = end + 1;
    return field;
  };
  while (at < text.size()) {
    FrameJob f;
    f.scenePath = line();
    f.camera = std::stoi(line());
    f.frame = std::stoi(line());
    f.frames = std::stoi(line());
    f.output = line();
    all.push_back(std::move(f));
  }
  return all;
}

struct FrameTotals {
  explicit FrameTotals(std::size_t frames, int ranks)
      : total(frames), progress(frames), ranks(static_cast<std::size_t>(ranks)) {}
  std::size_t total;
  FrameProgress progress;
  std::vector<RankTally> ranks;
};

// The tracer of the frame a thread renders, built again only when its frame changes: the one thread that renders
// on a rank (rank 0's render thread, a worker's tile thread) is its only caller.
class RunTracers {
 public:
  RunTracers(const FrameScene& scene, const std::vector<FrameJob>& frames, std::size_t first)
      : scene_(scene), frames_(frames), first_(first) {}
  const Tracer& operator()(int frame) {
    if (!current_ || frame != frame_) {
      const FrameJob& f = frames_[first_ + static_cast<std::size_t>(frame)];
      current_ = scene_.frame(f.frame, f.frames);
      frame_ = frame;
    }
    return current_->tracer;
  }

 private:
  const FrameScene& scene_;
  const std::vector<FrameJob>& frames_;
  std::size_t first_;
  std::unique_ptr<FrameTracer> current_;
  int frame_ = -1;
};

// The frames [first, end) of one scene on every rank: the scene loaded once, its frames dealt as units
// (frame_units.h); rank 0 writes each frame as its last unit comes in. Returns this rank's exit code.
int renderRun(const RenderJob& job, const std::vector<FrameJob>& frames, std::size_t first, std::size_t end,
              int rank, int ranks, ThreadPool& pool, std::vector<bool>& lost, FrameTotals& totals) {
  const RenderJob sceneJob = jobForFrame(job, frames[first]);
  DistributedScene distributed;
  if (const int failed = distributeScene(sceneJob, rank, ranks, distributed); failed != kExitOk) return failed;
  const BvhBuild build = memoryPlanFor(job, *distributed.scene).lean ? BvhBuild::Lean : BvhBuild::OneImage;
  const FrameScene scene(distributed.scene, distributed.settings, build);
  const Camera& camera = scene.scene().camera;  // every frame of a turntable keeps the lens: the same size
  const std::vector<WorkUnit> units = frameUnits(static_cast<int>(end - first), camera.width, camera.height, ranks);
  RunTracers tracers(scene, frames, first);
  const TracerFor tracerFor = [&tracers](int frame) -> const Tracer& { return tracers(frame); };
  // The run's first frame numbers it: a late result of an earlier run is recognised and dropped.
  const int round = static_cast<int>(first);
  if (rank != 0) return workOnUnits(units, tracerFor, rank, pool, round);
  int code = kExitOk;
  FrameAssembly assembly(units, [&](int frame, Image&& image) {
    const FrameJob& f = frames[first + static_cast<std::size_t>(frame)];
    code = writeFrameFile(f.output, std::move(image));
    if (code != kExitOk) return false;
    totals.progress.frameWritten(f.output, job.quiet);
    noteFrames(totals.progress.written(), totals.total);
    return true;
  });
  const ExchangeResult result = coordinateUnits(units, assembly, ranks, pool, tracerFor, round, lost);
  for (std::size_t r = 0; r < result.ranks.size(); ++r) {
    totals.ranks[r].busyMs += result.ranks[r].busyMs;
    totals.ranks[r].tiles += result.ranks[r].tiles;
    totals.ranks[r].frames += result.ranks[r].frames;
  }
  return code;
}

void printFrameSummary(const FrameTotals& totals, bool byScene) {
  double maxBusy = 0.0, sumBusy = 0.0;
  for (const RankTally& rank : totals.ranks) maxBusy = std::max(maxBusy, rank.busyMs), sumBusy += rank.busyMs;
  std::printf("time       %.1f s for %zu frames\n", totals.progress.seconds(), totals.progress.written());
  for (std::size_t r = 0; r < totals.ranks.size(); ++r)
    std::printf("rank %-5zu busy %.1f ms, %s%zu whole frames, %zu tiles\n", r, totals.ranks[r].busyMs,
                byScene ? (std::to_string(totals.ranks[r].scenes) + (totals.ranks[r].scenes == 1 ? " scene, " : " scenes, ")).c_str() : "", totals.ranks[r].frames,
                totals.ranks[r].tiles);
  std::printf("balance    %.3f (mean/max busy time)\n",
              maxBusy > 0.0 ? sumBusy / static_cast<double>(totals.ranks.size()) / maxBusy : 1.0);
}

}  // namespace

int runClusterFrames(const RenderJob& job, const std::vector<FrameJob>& planned, int planCode) {
  int rank = 0, ranks = 1;
  MPI_Comm_set_errhandler(MPI_COMM_WORLD, MPI_ERRORS_RETURN);
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &ranks);
  int code = planCode;
  const std::vector<FrameJob> frames = broadcastFrames(rank, planned, code);
  if (code != kExitOk) return code;
  ThreadPool pool(job.threads);
  std::vector<bool> lost(static_cast<std::size_t>(ranks), false);
  FrameTotals totals(frames.size(), ranks);
  if (rank == 0) {
    noteFrames(0, frames.size());
    handleSignalsOnRankZero();
  }
  // At least as many scenes as ranks: each dealt whole to one rank, which alone builds it (scene_batch.h). Fewer:
  // one after another, each tiled across every rank, so that none is idle.
  if (const std::vector<SceneRun> runs = sceneRuns(frames); runs.size() > 1 && runs.size() >= static_cast<std::size_t>(ranks)) {
    code = rank == 0 ? dealScenes(job, frames, runs, pool, totals.progress, totals.ranks) : workOnScenes(rank, pool);
    if (rank == 0 && code == kExitOk && !job.quiet) printFrameSummary(totals, true);
    return code;
  }
  for (std::size_t first = 0; first < frames.size();) {
    std::size_t end = first;
    while (end < frames.size() && sameSceneAndCamera(frames[end], frames[first])) ++end;
    if (const int failed = renderRun(job, frames, first, end, rank, ranks, pool, lost, totals); failed != kExitOk)
      return failed;
    first = end;
    // The next scene's broadcast is collective and would wait for a lost rank for ever.
    if (peerLost() && first < frames.size()) {
      if (rank == 0)
        std::fprintf(stderr, "rayview: error: a rank was lost; %zu of %zu frames written, %zu not rendered (rerun "
                     "the same command to render them)\n", totals.progress.written(), frames.size(),
                     frames.size() - totals.progress.written());
      return kExitIoFailure;
    }
  }
  if (rank == 0 && !job.quiet) printFrameSummary(totals, false);
  return kExitOk;
}

}  // namespace rayview::cluster
