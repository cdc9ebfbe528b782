#include "scene_distribution.h"

#include <mpi.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include "mpi_link.h"
#include "rayview/exit_codes.h"
#include "rayview/image.h"
#include "rayview/scene_open.h"
#include "rayview/scene_source.h"
#include "scene_hash.h"
#include "view_codec.h"

namespace rayview::cluster {
namespace {

// MPI counts are ints: big buffers go in pieces.
constexpr std::size_t kPiece = std::size_t{1} << 30;

void broadcastBytes(void* data, std::size_t bytes) {
  auto* p = static_cast<char*>(data);
  for (std::size_t at = 0; at < bytes; at += kPiece)
    broadcastGently(p + at, static_cast<int>(std::min(kPiece, bytes - at)), MPI_BYTE);
}

// Every other rank: the scene from rank 0's bytes ("" on success, else why not).
std::string decodeOnRank(const RenderJob& job, const Bytes& geometry, const Bytes& parameters, Scene& scene,
                         RenderSettings& settings) {
  try {
    ShippedGeometry shipped = decodeGeometry(geometry.data(), geometry.size());
    static_cast<SceneGeometry&>(scene) = std::move(*shipped.geometry);
    Snapshot snapshot = decodeSnapshot(parameters.data(), parameters.size());
    scene.parameters() = std::move(snapshot.parameters);
    settings = snapshot.settings;
    scene.sourcePath = job.scene();
  } catch (const CodecError& error) {
    return std::string("rayview: error: the scene from rank 0 is malformed: ") + error.what();
  } catch (const std::bad_alloc&) {
    return "rayview: error: out of memory receiving " + job.scene();
  }
  return {};
}

struct RankCheck {
  std::uint64_t hash = 0;
  std::int32_t loaded = 0;
  std::int32_t unused = 0;
};

// Rank 0: the verdict from every rank's check, the one message printed. Workers that failed send their text.
int verdictOnRankZero(const std::vector<RankCheck>& checks, const std::string& ownError) {
  if (!ownError.empty()) {
    std::fprintf(stderr, "%s\n", ownError.c_str());
    return kExitBadInput;
  }
  for (std::size_t r = 1; r < checks.size(); ++r) {
    if (checks[r].loaded) continue;
    MPI_Status status;
    int length = 0;
    MPI_Probe(static_cast<int>(r), kTagLoadError, MPI_COMM_WORLD, &status);
    MPI_Get_count(&status, MPI_CHAR, &length);
    std::string text(static_cast<std::size_t>(length), '\0');
    MPI_Recv(text.data(), length, MPI_CHAR, static_cast<int>(r), kTagLoadError, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    std::fprintf(stderr, "rayview: rank %zu: %s\n", r, text.c_str());
    return kExitBadInput;
  }
  for (std::size_t r = 1; r < checks.size(); ++r)
    if (checks[r].hash != checks[0].hash) {
      std::fprintf(stderr, "rayview: error: rank %zu loaded a scene that differs from rank 0's (hash %016llx, not %016llx)\n",
                   r, static_cast<unsigned long long>(checks[r].hash), static_cast<unsigned long long>(checks[0].hash));
      return kExitIoFailure;
    }
  return kExitOk;
}

}  // namespace

int loadSceneOnRankZero(const RenderJob& job, LoadedScene& loaded, std::string& message) {
  if (const std::string problem = renderOutputProblem(job.output, job.scene()); !problem.empty()) {
    message = "rayview: error: " + problem;
    return kExitBadInput;
  }
  try {
    loaded = openScene(job.scene(), job.open, nullptr, job.threads);
  } catch (const SceneError& error) {
    message = error.what();
    return kExitBadInput;
  } catch (const std::bad_alloc&) {
    message = "rayview: error: out of memory loading " + job.scene();
    return kExitOutOfMemory;
  }
  return kExitOk;
}

int distributeScene(const RenderJob& job, int rank, int ranks, DistributedScene& out) {
  const auto start = std::chrono::steady_clock::now();
  // Rank 0 alone reads and parses; the others receive the loaded arrays and the parameters with the knobs applied
  // (cluster/view_codec.h, 36 bytes a triangle instead of ~53 of text), so they parse nothing.
  LoadedScene loaded;
  Bytes geometry, parameters;
  std::int64_t header[3] = {kExitOk, 0, 0};  // exit code, byte counts
  if (rank == 0) {
    std::string message;
    header[0] = loadSceneOnRankZero(job, loaded, message);
    if (header[0] != kExitOk) std::fprintf(stderr, "%s\n", message.c_str());
    if (header[0] == kExitOk) {
      applyKnobs(job.knobs, {&loaded.scene.parameters(), &out.settings});
      if (ranks > 1) {
        geometry = encodeGeometry(loaded.scene.geometry(), loaded.scene.camera.position, out.settings.accel);
        parameters = encodeSnapshot(loaded.scene.parameters(), out.settings);
      }
      header[1] = static_cast<std::int64_t>(geometry.size());
      header[2] = static_cast<std::int64_t>(parameters.size());
    }
  }
  broadcastGently(header, 3, MPI_INT64_T);
  if (header[0] != kExitOk) return static_cast<int>(header[0]);
  geometry.resize(static_cast<std::size_t>(header[1]));
  parameters.resize(static_cast<std::size_t>(header[2]));
  broadcastBytes(geometry.data(), geometry.size());
  broadcastBytes(parameters.data(), parameters.size());
  const std::string error =
      rank == 0 ? std::string() : decodeOnRank(job, geometry, parameters, loaded.scene, out.settings);
  Bytes().swap(geometry);

  RankCheck own{error.empty() ? sceneHash(loaded.scene) : 0, error.empty() ? 1 : 0, 0};
  std::vector<RankCheck> checks(rank == 0 ? static_cast<std::size_t>(ranks) : 0);
  gatherGently(&own, sizeof own, checks.data());
  // Short enough to go eagerly: a send rank 0 does not receive (not the first failure) never blocks.
  if (rank != 0 && !error.empty())
    MPI_Send(error.data(), static_cast<int>(std::min<std::size_t>(error.size(), 2000)), MPI_CHAR, 0, kTagLoadError,
             MPI_COMM_WORLD);
  int verdict = rank == 0 ? verdictOnRankZero(checks, error) : kExitOk;
  broadcastGently(&verdict, 1, MPI_INT);
  if (verdict != kExitOk) return verdict;

  if (rank == 0 && !job.quiet)
    for (const Diagnostic& warning : loaded.warnings) std::fprintf(stderr, "%s\n", warning.format().c_str());
  out.scene = std::make_shared<const Scene>(std::move(loaded.scene));
  out.loadMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return kExitOk;
}

}  // namespace rayview::cluster
