#pragma once
// The messages of a distributed render and the waits that never block on a rank that may be gone.

#include <mpi.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <thread>
#include <vector>

#include "link_times.h"

namespace rayview::cluster {

enum Tag : int {
  kTagTile = 1,       // rank 0 -> worker: one int32, a tile index, or kNoMoreTiles
  kTagResult = 2,     // worker -> rank 0: TileResultHeader, then the tile's RGB rows
  kTagAlive = 3,      // worker -> rank 0, while it renders: nothing (a heartbeat)
  kTagLoadError = 4,  // worker -> rank 0: the text of its load error
  // A batch dealt by scene (scene_batch.h):
  kTagScene = 5,        // rank 0 -> worker: an int64, the size of the scene order that follows
  kTagSceneBytes = 6,   // rank 0 -> worker: the scene order (scene_orders.h), in pieces of at most 1 GiB
  kTagSceneResult = 7,  // worker -> rank 0: SceneResultHeader, then the frame's RGB rows
  kTagSceneEnd = 8,     // rank 0 -> worker: two int32, the exit code and whether a rank was lost
  kTagNudge = 9,        // rank 0 -> idle worker: nothing (rank 0 is alive)
};

inline constexpr std::int32_t kNoMoreTiles = -1;
// The same, and a rank was lost: end without MPI_Finalize, which would wait for it.
inline constexpr std::int32_t kNoMoreTilesRankLost = -3;

struct TileResultHeader {
  std::int32_t tile = 0;
  std::int32_t frame = 0;  // which of the job's frames: a late result of an earlier frame is dropped
  double busyMs = 0.0;
  std::uint64_t camera = 0, shadow = 0, reflection = 0;
};

// A message waiting from `source` (MPI_ANY_SOURCE) with `tag` (MPI_ANY_TAG)? Fills `status` when there is.
inline bool messageWaiting(int source, int tag, MPI_Status& status) {
  int flag = 0;
  return MPI_Iprobe(source, tag, MPI_COMM_WORLD, &flag, &status) == MPI_SUCCESS && flag != 0;
}

// Receives a message `probed` announced, waiting at most `patience`: a large message is read from the sender's
// memory, and a blocking receive from a sender that died meanwhile would never return. False: given up (the
// buffer then belongs to MPI for good and must not be freed).
inline bool receiveWithin(void* buffer, int bytes, const MPI_Status& probed, std::chrono::milliseconds patience) {
  MPI_Request request;
  MPI_Irecv(buffer, bytes, MPI_BYTE, probed.MPI_SOURCE, probed.MPI_TAG, MPI_COMM_WORLD, &request);
  const auto deadline = std::chrono::steady_clock::now() + patience;
  for (int done = 0;;) {
    MPI_Test(&request, &done, MPI_STATUS_IGNORE);
    if (done) return true;
    if (std::chrono::steady_clock::now() > deadline) return false;
    std::this_thread::sleep_for(kProbePause);
  }
}

// Waits for `request` without spinning a core: OpenMPI's blocking calls poll without yielding, which on a node
// with more ranks than cores takes the CPU from the rank whose work is being waited for (rank 0's parse).
inline void waitGently(MPI_Request& request) {
  auto pause = std::chrono::duration_cast<std::chrono::microseconds>(kProbePause);
  for (int done = 0;;) {
    MPI_Test(&request, &done, MPI_STATUS_IGNORE);
    if (done) return;
    std::this_thread::sleep_for(pause);
    pause = std::min<std::chrono::microseconds>(pause * 2, kLongestProbePause);
  }
}

// MPI_Bcast from rank 0 and MPI_Gather at rank 0, waited for gently.
inline void broadcastGently(void* buffer, int count, MPI_Datatype type) {
  MPI_Request request;
  MPI_Ibcast(buffer, count, type, 0, MPI_COMM_WORLD, &request);
  waitGently(request);
}
inline void gatherGently(const void* send, int bytes, void* receive) {
  MPI_Request request;
  MPI_Igather(send, bytes, MPI_BYTE, receive, bytes, MPI_BYTE, 0, MPI_COMM_WORLD, &request);
  waitGently(request);
}

// A buffer MPI may still write or read (a receive or send given up on): kept until the process ends.
inline void keepForMpi(std::shared_ptr<const void> buffer) {
  static std::mutex mutex;
  static std::vector<std::shared_ptr<const void>> kept;
  std::lock_guard lock(mutex);
  kept.push_back(std::move(buffer));
}

// One message from any rank, read into `inbox` (resized to its size plus one byte, so that an empty message has a
// buffer too).
struct Arrival {
  int source = 0;
  int tag = 0;
  std::size_t bytes = 0;
  bool whole = true;  // false: the sender fell silent mid-message, and `inbox` is a new, empty buffer
};
// nullopt when no message is waiting. A message not whole within `patience` is given up on (its buffer kept for MPI).
inline std::optional<Arrival> receiveAny(std::vector<std::uint8_t>& inbox, std::chrono::milliseconds patience) {
  MPI_Status status;
  if (!messageWaiting(MPI_ANY_SOURCE, MPI_ANY_TAG, status)) return std::nullopt;
  int bytes = 0;
  MPI_Get_count(&status, MPI_BYTE, &bytes);
  inbox.resize(static_cast<std::size_t>(bytes) + 1);
  Arrival arrival{status.MPI_SOURCE, status.MPI_TAG, static_cast<std::size_t>(bytes), true};
  if (!receiveWithin(inbox.data(), bytes, status, patience)) {
    keepForMpi(std::make_shared<std::vector<std::uint8_t>>(std::move(inbox)));
    inbox = {};
    arrival.whole = false;
  }
  return arrival;
}

}  // namespace rayview::cluster
