#include <mpi.h>
#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <string>

#include "cluster_runs.h"
#include "rayview/exit_codes.h"
#include "rayview/frame_scene.h"
#include "rayview/image.h"
#include "rayview/prepared_scene.h"
#include "rayview/thread_pool.h"
#include "rayview/tracer.h"
#include "scene_distribution.h"
#include "tile_exchange.h"
#include "tile_plan.h"

namespace rayview::cluster {
namespace {

using Clock = std::chrono::steady_clock;

double msSince(Clock::time_point start) { return std::chrono::duration<double, std::milli>(Clock::now() - start).count(); }

// Async-signal-safe decimal.
char* writeNumber(char* at, std::size_t value) {
  char digits[24];
  int n = 0;
  do digits[n++] = static_cast<char>('0' + value % 10);
  while ((value /= 10) != 0);
  while (n > 0) *at++ = digits[--n];
  return at;
}

// Only async-signal-safe calls: the counters are lock-free atomics.
extern "C" void onRankZeroSignal(int signal) {
  if (const char* temporary = temporaryFileInProgress()) ::unlink(temporary);
  char line[200];
  char* at = line;
  auto put = [&](const char* text) { while (*text) *at++ = *text++; };
  put("rayview: rank 0 stopped by signal ");
  at = writeNumber(at, static_cast<std::size_t>(signal));
  put(": ");
  if (framesPlanned() > 0) {
    at = writeNumber(at, framesWritten());
    put(" of ");
    at = writeNumber(at, framesPlanned());
    put(" frames written (rerun the same command to render the rest)\n");
  } else {
    at = writeNumber(at, tilesPlanned() - tilesPlaced());
    put(" of ");
    at = writeNumber(at, tilesPlanned());
    put(" tiles not finished; no image written\n");
  }
  (void)!::write(2, line, static_cast<std::size_t>(at - line));
  ::_exit(128 + signal);
}

}  // namespace

void handleSignalsOnRankZero() {
  struct sigaction action {};
  action.sa_handler = onRankZeroSignal;
  sigemptyset(&action.sa_mask);
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
}

namespace {

std::string countedText(std::size_t count, const char* singular) {
  return std::to_string(count) + " " + singular + (count == 1 ? "" : "s");
}

void printSummary(const RenderJob& job, const Scene& scene, const PreparedGeometry& geometry, int threads,
                  const ExchangeResult& result, double loadMs, double renderMs, double writeMs, std::size_t tiles) {
  RayCounts rays;
  double maxBusy = 0.0, sumBusy = 0.0;
  for (const RankTally& rank : result.ranks) {
    rays += rank.rays;
    maxBusy = std::max(maxBusy, rank.busyMs);
    sumBusy += rank.busyMs;
  }
  const std::size_t ranks = result.ranks.size();
  std::printf("scene      %s: %s, %dx%d\n", job.scene().empty() ? "default (embedded)" : job.scene().c_str(),
              countedText(scene.triangles.size(), "triangle").c_str(), scene.camera.width, scene.camera.height);
  std::printf("cluster    %s x %s, %s of %dx%d, accel %s\n", countedText(ranks, "rank").c_str(),
              countedText(static_cast<std::size_t>(threads), "thread").c_str(), countedText(tiles, "tile").c_str(),
              clusterTileEdge(scene.camera.width, scene.camera.height, static_cast<int>(ranks)),
              clusterTileEdge(scene.camera.width, scene.camera.height, static_cast<int>(ranks)),
              std::string(toString(geometry.accel->kind())).c_str());
  // Load on rank 0 counts its read, the broadcast, its load and the check of every rank's hash.
  std::printf("time       load %.1f ms, BVH build %.1f ms, render %.1f ms, write %.1f ms\n",
              loadMs, geometry.buildMs, renderMs, writeMs);
  for (std::size_t r = 0; r < ranks; ++r)
    std::printf("rank %-5zu busy %.1f ms, %s%s\n", r, result.ranks[r].busyMs,
                countedText(result.ranks[r].tiles, "tile").c_str(), result.ranks[r].lost ? " (lost)" : "");
  std::printf("balance    %.3f (mean/max busy time)\n", maxBusy > 0.0 ? sumBusy / static_cast<double>(ranks) / maxBusy : 1.0);
  std::printf("rays       total %llu, %.2f Mrays/s\n", static_cast<unsigned long long>(rays.total()),
              renderMs > 0.0 ? static_cast<double>(rays.total()) / (renderMs * 1000.0) : 0.0);
  std::printf("wrote      %s\n", std::filesystem::absolute(job.output).c_str());
}

}  // namespace

int runClusterRender(const RenderJob& job) {
  int rank = 0, ranks = 1;
  MPI_Comm_set_errhandler(MPI_COMM_WORLD, MPI_ERRORS_RETURN);
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &ranks);
  if (rank == 0) handleSignalsOnRankZero();

  DistributedScene distributed;
  if (const int code = distributeScene(job, rank, ranks, distributed); code != kExitOk) return code;
  RenderSettings settings = distributed.settings;
  const Scene& scene = *distributed.scene;
  // Built for memory, as a single process's `rayview render` builds it: the same back-end, the same image.
  const BvhBuild build = memoryPlanFor(job, scene).lean ? BvhBuild::Lean : BvhBuild::OneImage;
  auto geometry = prepareGeometry(distributed.scene, settings.accel, build);
  if (!geometry->accelFallback.empty()) {
    if (rank == 0)
      std::fprintf(stderr, "%s: warning: %s; rendering with the reference BVH instead\n",
                   job.scene().empty() ? "default scene" : job.scene().c_str(), geometry->accelFallback.c_str());
    settings.accel = AccelKind::Reference;
  }
  ThreadPool pool(job.threads);
  const Tracer tracer(scene.parameters(), *geometry, settings);
  const std::vector<Tile> tiles = clusterTiles(scene.camera.width, scene.camera.height, ranks);
  const std::vector<WorkUnit> units = tileUnits(tiles);
  const TracerFor tracerFor = [&tracer](int) -> const Tracer& { return tracer; };
  if (rank != 0) return workOnUnits(units, tracerFor, rank, pool, 0);

  Image image;
  FrameAssembly assembly(units, [&image](int, Image&& finished) {
    image = std::move(finished);
    return true;
  });
  const auto renderStart = Clock::now();
  std::vector<bool> lost(static_cast<std::size_t>(ranks), false);
  const ExchangeResult result = coordinateUnits(units, assembly, ranks, pool, tracerFor, 0, lost);
  const double renderMs = msSince(renderStart);
  const auto writeStart = Clock::now();
  try {
    writeImageFile(job.output, std::move(image));
  } catch (const ImageIoError& error) {
    std::fprintf(stderr, "rayview: error: %s\n", error.what());
    return kExitIoFailure;
  }
  if (!job.quiet)
    printSummary(job, scene, *geometry, pool.size(), result, distributed.loadMs, renderMs, msSince(writeStart),
                 tiles.size());
  return kExitOk;
}

}  // namespace rayview::cluster
