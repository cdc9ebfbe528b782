#include <mpi.h>

#include <chrono>
#include <cstdio>
#include <string>
#include <system_error>

#include "cluster_job.h"
#include "exit_codes.h"
#include "rayview/image.h"
#include "rayview/prepared_scene.h"
#include "rayview/scene_bounds.h"
#include "rayview/thread_pool.h"
#include "rayview/tracer.h"
#include "scene_distribution.h"
#include "tile_exchange.h"
#include "tile_plan.h"

namespace rayview::cluster {
namespace {

using Clock = std::chrono::steady_clock;

// Rank 0's frames to every rank, as text: scene, frame, frames, output, one field a line.
std::vector<ClusterFrame> broadcastFrames(int rank, const std::vector<ClusterFrame>& frames, int& code) {
  std::string text;
  if (rank == 0)
    for (const ClusterFrame& f : frames)
      text += f.scenePath + '\n' + std::to_string(f.frame) + '\n' + std::to_string(f.frames) + '\n' + f.output.string() + '\n';
  std::int64_t header[2] = {code, static_cast<std::int64_t>(text.size())};
  MPI_Bcast(header, 2, MPI_INT64_T, 0, MPI_COMM_WORLD);
  code = static_cast<int>(header[0]);
  if (code != kExitOk) return {};
  text.resize(static_cast<std::size_t>(header[1]));
  MPI_Bcast(text.data(), static_cast<int>(text.size()), MPI_CHAR, 0, MPI_COMM_WORLD);
  std::vector<ClusterFrame> all;
  std::size_t at = 0;
  auto line = [&] {
    const std::size_t end = text.find('\n', at);
    std::string field = text.substr(at, end - at);
    at = end + 1;
    return field;
  };
  while (at < text.size()) {
    ClusterFrame f;
    f.scenePath = line();
    f.frame = std::stoi(line());
    f.frames = std::stoi(line());
    f.output = line();
    all.push_back(std::move(f));
  }
  return all;
}

struct FrameTotals {
  std::vector<RankTally> ranks;
  std::size_t written = 0;
  Clock::time_point start = Clock::now();
};

// Rank 0's side of one frame: deal, write, say how far the job is.
int coordinateFrame(const Tracer& tracer, const Camera& camera, const ClusterFrame& frame, int sequence, int ranks,
                    ThreadPool& pool, std::vector<bool>& lost, FrameTotals& totals, std::size_t total, bool quiet) {
  Image image(camera.width, camera.height);
  const ExchangeResult result =
      coordinateTiles(tracer, clusterTiles(camera.width, camera.height, ranks), ranks, pool, image, sequence, lost);
  for (std::size_t r = 0; r < result.ranks.size(); ++r) {
    totals.ranks[r].busyMs += result.ranks[r].busyMs;
    totals.ranks[r].tiles += result.ranks[r].tiles;
  }
  try {
    std::error_code ignored;
    if (frame.output.has_parent_path()) std::filesystem::create_directories(frame.output.parent_path(), ignored);
    writeImageFile(frame.output, std::move(image));
  } catch (const ImageIoError& error) {
    std::fprintf(stderr, "rayview: error: %s\n", error.what());
    return kExitIoFailure;
  }
  ++totals.written;
  if (!quiet) {
    const double elapsed = std::chrono::duration<double>(Clock::now() - totals.start).count();
    const std::size_t left = total - totals.written;
    std::fprintf(stderr, "rayview: frame %zu of %zu written (%s); %zu remaining, about %.0f s left\n", totals.written,
                 total, frame.output.filename().c_str(), left,
                 elapsed / static_cast<double>(totals.written) * static_cast<double>(left));
  }
  return kExitOk;
}

void printFrameSummary(const FrameTotals& totals) {
  double maxBusy = 0.0, sumBusy = 0.0;
  for (const RankTally& rank : totals.ranks) maxBusy = std::max(maxBusy, rank.busyMs), sumBusy += rank.busyMs;
  std::printf("time       %.1f s for %zu frames\n", std::chrono::duration<double>(Clock::now() - totals.start).count(),
              totals.written);
  for (std::size_t r = 0; r < totals.ranks.size(); ++r)
    std::printf("rank %-5zu busy %.1f ms, %zu tiles\n", r, totals.ranks[r].busyMs, totals.ranks[r].tiles);
  std::printf("balance    %.3f (mean/max busy time)\n",
              maxBusy > 0.0 ? sumBusy / static_cast<double>(totals.ranks.size()) / maxBusy : 1.0);
}

}  // namespace

int runClusterFrames(const ClusterJob& job, const std::vector<ClusterFrame>& planned, int planCode) {
  int rank = 0, ranks = 1;
  MPI_Comm_set_errhandler(MPI_COMM_WORLD, MPI_ERRORS_RETURN);
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &ranks);
  int code = planCode;
  const std::vector<ClusterFrame> frames = broadcastFrames(rank, planned, code);
  if (code != kExitOk) return code;
  ThreadPool pool(job.threads);
  std::vector<bool> lost(static_cast<std::size_t>(ranks), false);
  FrameTotals totals;
  totals.ranks.resize(static_cast<std::size_t>(ranks));
  for (std::size_t next = 0; next < frames.size();) {
    ClusterJob sceneJob = job;
    sceneJob.scenePath = frames[next].scenePath;
    sceneJob.output = frames[next].output;
    DistributedScene distributed;
    if (const int failed = distributeScene(sceneJob, rank, ranks, distributed); failed != kExitOk) return failed;
    RenderSettings settings = distributed.settings;
    const auto geometry = prepareGeometry(distributed.scene, settings.accel, BvhLayout::Fast);
    if (!geometry->accelFallback.empty()) settings.accel = AccelKind::Reference;
    const Scene& scene = *distributed.scene;
    const glm::dvec3 pivot = orbitPivot(scene.camera, sceneBounds(scene));
    for (; next < frames.size() && frames[next].scenePath == sceneJob.scenePath; ++next) {
      SceneParameters parameters = scene.parameters();
      parameters.camera = turntableCamera(scene.camera, pivot, frames[next].frame, frames[next].frames);
      const Tracer tracer(parameters, *geometry, settings);
      const Camera& camera = parameters.camera;
      const int sequence = static_cast<int>(next);
      if (rank != 0) {
        if (const int failed = workOnTiles(tracer, clusterTiles(camera.width, camera.height, ranks), rank, pool, sequence);
            failed != kExitOk || peerLost())
          return failed;
        continue;
      }
      if (const int failed = coordinateFrame(tracer, camera, frames[next], sequence, ranks, pool, lost, totals,
                                             frames.size(), job.quiet);
          failed != kExitOk)
        return failed;
      if (peerLost()) {
        std::fprintf(stderr, "rayview: error: a rank was lost; %zu of %zu frames written, %zu not rendered (rerun the "
                     "same command to render them)\n", totals.written, frames.size(), frames.size() - totals.written);
        return kExitIoFailure;
      }
    }
  }
  if (rank == 0 && !job.quiet) printFrameSummary(totals);
  return kExitOk;
}

}  // namespace rayview::cluster
