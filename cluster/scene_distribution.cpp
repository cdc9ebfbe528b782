#include "scene_distribution.h"

#include <mpi.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include "mpi_link.h"
#include "exit_codes.h"
#include "rayview/file_read.h"
#include "rayview/image.h"
#include "rayview/scene_source.h"
#include "scene_hash.h"

namespace rayview::cluster {
namespace {

// MPI counts are ints: big buffers go in pieces.
constexpr std::size_t kPiece = std::size_t{1} << 30;

void broadcastBytes(void* data, std::size_t bytes) {
  auto* p = static_cast<char*>(data);
  for (std::size_t at = 0; at < bytes; at += kPiece)
    MPI_Bcast(p + at, static_cast<int>(std::min(kPiece, bytes - at)), MPI_BYTE, 0, MPI_COMM_WORLD);
}

// Rank 0: the output checks and the scene's bytes. Returns the exit code (printed) when the job cannot start.
int readOnRankZero(const ClusterJob& job, std::string& bytes) {
  if (const std::string problem = renderOutputProblem(job.output, job.scenePath); !problem.empty()) {
    std::fprintf(stderr, "rayview: error: %s\n", problem.c_str());
    return kExitBadInput;
  }
  if (job.scenePath.empty()) {
    bytes = std::string(defaultSceneXml());
    return kExitOk;
  }
  detail::UserFileRead read = detail::readUserFile(job.scenePath, std::uintmax_t{1} << 36);
  if (read.problem.empty()) {
    bytes = std::move(read.bytes);
    return kExitOk;
  }
  // The loader says why in its usual words.
  try {
    loadSceneOrDefault(job.scenePath, LoadOptions{});
  } catch (const SceneError& error) {
    std::fprintf(stderr, "%s\n", error.what());
    return kExitBadInput;
  }
  std::fprintf(stderr, "rayview: error: %s %s\n", job.scenePath.c_str(), read.problem.c_str());
  return kExitBadInput;
}

// Every rank: the scene from the bytes (rank 0 from its file, as a single process does, with the texture).
std::string loadOnRank(const ClusterJob& job, int rank, const std::string& bytes, LoadedScene& loaded) {
  LoadOptions options;
  options.strict = job.strict;
  try {
    if (rank == 0) {
      loaded = loadSceneOrDefault(job.scenePath, options);
    } else {
      options.loadTexture = false;
      const std::filesystem::path path(job.scenePath);
      loaded = loadSceneText(bytes, job.scenePath.empty() ? kDefaultSceneName : job.scenePath, path.parent_path(),
                             options);
    }
  } catch (const SceneError& error) {
    return error.what();
  } catch (const std::bad_alloc&) {
    return "rayview: error: out of memory loading " + job.scenePath;
  }
  return {};
}

// Rank 0's decoded texture to every rank.
void broadcastTexture(int rank, LoadedScene& loaded) {
  std::int64_t shape[3] = {0, 0, 0};
  if (rank == 0 && loaded.scene.texture) shape[0] = 1, shape[1] = loaded.scene.texture->width, shape[2] = loaded.scene.texture->height;
  MPI_Bcast(shape, 3, MPI_INT64_T, 0, MPI_COMM_WORLD);
  if (shape[0] == 0) return;
  if (rank != 0) {
    Texture texture;
    texture.width = static_cast<int>(shape[1]);
    texture.height = static_cast<int>(shape[2]);
    texture.rgb.resize(static_cast<std::size_t>(shape[1] * shape[2] * 3));
    loaded.scene.texture = std::move(texture);
  }
  broadcastBytes(loaded.scene.texture->rgb.data(), loaded.scene.texture->rgb.size());
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

int distributeScene(const ClusterJob& job, int rank, int ranks, DistributedScene& out) {
  const auto start = std::chrono::steady_clock::now();
  std::string bytes;
  std::int64_t header[2] = {kExitOk, 0};  // exit code, byte count
  if (rank == 0) {
    header[0] = readOnRankZero(job, bytes);
    header[1] = static_cast<std::int64_t>(bytes.size());
  }
  MPI_Bcast(header, 2, MPI_INT64_T, 0, MPI_COMM_WORLD);
  if (header[0] != kExitOk) return static_cast<int>(header[0]);
  bytes.resize(static_cast<std::size_t>(header[1]));
  broadcastBytes(bytes.data(), bytes.size());

  LoadedScene loaded;
  const std::string error = loadOnRank(job, rank, bytes, loaded);
  std::string().swap(bytes);
  broadcastTexture(rank, loaded);
  applyKnobs(job.knobs, {&loaded.scene.parameters(), &out.settings});

  RankCheck own{error.empty() ? sceneHash(loaded.scene) : 0, error.empty() ? 1 : 0, 0};
  std::vector<RankCheck> checks(rank == 0 ? static_cast<std::size_t>(ranks) : 0);
  MPI_Gather(&own, sizeof own, MPI_BYTE, checks.data(), sizeof own, MPI_BYTE, 0, MPI_COMM_WORLD);
  // Short enough to go eagerly: a send rank 0 does not receive (not the first failure) never blocks.
  if (rank != 0 && !error.empty())
    MPI_Send(error.data(), static_cast<int>(std::min<std::size_t>(error.size(), 2000)), MPI_CHAR, 0, kTagLoadError,
             MPI_COMM_WORLD);
  int verdict = rank == 0 ? verdictOnRankZero(checks, error) : kExitOk;
  MPI_Bcast(&verdict, 1, MPI_INT, 0, MPI_COMM_WORLD);
  if (verdict != kExitOk) return verdict;

  if (rank == 0 && !job.quiet)
    for (const Diagnostic& warning : loaded.warnings) std::fprintf(stderr, "%s\n", warning.format().c_str());
  out.scene = std::make_shared<const Scene>(std::move(loaded.scene));
  out.loadMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return kExitOk;
}

}  // namespace rayview::cluster
