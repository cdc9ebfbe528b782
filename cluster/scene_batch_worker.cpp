#include <mpi.h>

#include <chrono>
#include <cstdio>
#include <cstring>
#include <memory>
#include <string>
#include <thread>

#include "rayview/exit_codes.h"
#include "mpi_link.h"
#include "mpi_outbox.h"
#include "scene_batch.h"
#include "scene_render_thread.h"

namespace rayview::cluster {
namespace {

using Clock = std::chrono::steady_clock;
constexpr std::size_t kPiece = std::size_t{1} << 30;
constexpr auto kPatience = std::chrono::duration_cast<std::chrono::milliseconds>(kRankZeroLostAfter);

// The scene from rank 0's order, as distributeScene's workers decode it; throws CodecError.
SceneToRender decodeScene(const SceneOrder& order) {
  Scene scene;
  ShippedGeometry shipped = decodeGeometry(order.geometry.data(), order.geometry.size());
  static_cast<SceneGeometry&>(scene) = std::move(*shipped.geometry);
  Snapshot snapshot = decodeSnapshot(order.parameters.data(), order.parameters.size());
  scene.parameters() = std::move(snapshot.parameters);
  scene.sourcePath = order.scenePath;
  return {std::make_shared<const Scene>(std::move(scene)), snapshot.settings};
}


class SceneWorker {
 public:
  explicit SceneWorker(ThreadPool& pool) : renderer_(pool) {}

  int run(int rank) {
    for (;;) {
      if (!readMessages()) break;
      // The end can come while a copy of a scene another rank finished first is still rendering: it is not needed.
      if (ended_) return completeWithin(pending_, kPatience) ? code_ : kExitIoFailure;
      if (left_ > 0) {
        if (!answer()) break;
        continue;
      }
      if (Clock::now() - lastFromZero_ > kRankZeroLostAfter) break;
      std::this_thread::sleep_for(kProbePause);
    }
    notePeerLost();
    std::fprintf(stderr, "rayview: rank %d: no word from rank 0 for %.0f s; stopping\n", rank,
                 std::chrono::duration<double>(kRankZeroLostAfter).count());
    return kExitIoFailure;
  }

 private:
  // Every message rank 0 has sent, up to its end; false when rank 0 died in the middle of one.
  bool readMessages() {
    MPI_Status status;
    while (!ended_ && messageWaiting(0, MPI_ANY_TAG, status)) {
      lastFromZero_ = Clock::now();
      int bytes = 0;
      MPI_Get_count(&status, MPI_BYTE, &bytes);
      Bytes message(static_cast<std::size_t>(bytes));
      if (!receiveWithin(message.data(), bytes, status, kPatience)) return false;
      if (status.MPI_TAG == kTagScene && message.size() == sizeof(std::int64_t)) {
        std::int64_t size = 0;
        std::memcpy(&size, message.data(), sizeof size);
        if (!receiveScene(static_cast<std::size_t>(size))) return false;
      } else if (status.MPI_TAG == kTagSceneEnd && message.size() == 2 * sizeof(std::int32_t)) {
        std::int32_t end[2];
        std::memcpy(end, message.data(), sizeof end);
        code_ = end[0];
        if (end[1] != 0) notePeerLost();
        ended_ = true;
      }
    }
    return true;
  }

  bool receiveScene(std::size_t size) {
    auto bytes = std::make_shared<Bytes>(size);
    for (std::size_t at = 0; at < size; at += kPiece) {
      MPI_Status status;
      const auto deadline = Clock::now() + kRankZeroLostAfter;
      while (!messageWaiting(0, kTagSceneBytes, status))
        if (Clock::now() > deadline) return false;
        else std::this_thread::sleep_for(kProbePause);
      if (!receiveWithin(bytes->data() + at, static_cast<int>(std::min(kPiece, size - at)), status, kPatience))
        return false;
    }
    lastFromZero_ = Clock::now();
    std::shared_ptr<SceneOrder> order;
    try {
      order = std::make_shared<SceneOrder>(decodeSceneOrder(bytes->data(), bytes->size()));
    } catch (const CodecError& error) {
      return sendError(std::string("rayview: error: the scene from rank 0 is malformed: ") + error.what()), true;
    }
    bytes.reset();
    left_ = order->frames.size() / 2;
    renderer_.start({order->run, [order] {
                       try {
                         return decodeScene(*order);
                       } catch (const CodecError& error) {
                         throw CodecError(std::string("rayview: error: the scene from rank 0 is malformed: ") + error.what());
                       }
                     },
                     order->frames, true});
    return true;
  }

  void sendError(const std::string& text) {
    // Short enough to go eagerly.
    MPI_Send(text.data(), static_cast<int>(std::min<std::size_t>(text.size(), 2000)), MPI_CHAR, 0, kTagLoadError,
             MPI_COMM_WORLD);
  }

  // While a scene renders: each finished frame goes to rank 0, and a heartbeat when none finished for a while.
  bool answer() {
    auto done = renderer_.next(std::chrono::duration_cast<std::chrono::milliseconds>(kAliveEvery));
    if (!done) {
      MPI_Send(nullptr, 0, MPI_BYTE, 0, kTagAlive, MPI_COMM_WORLD);
      return true;
    }
    lastFromZero_ = Clock::now();  // rank 0's silence counts from when this rank next waits on it
    if (!done->error.empty()) {
      left_ = 0;
      sendError(done->error);
      return true;
    }
    --left_;
    if (!completeWithin(pending_, kPatience)) return false;
    const SceneResultHeader header{done->run, done->frame, done->busyMs, done->hash,
                                   done->rays.camera, done->rays.shadow, done->rays.reflection};
    message_.resize(sizeof header + done->image.rgb.size());
    std::memcpy(message_.data(), &header, sizeof header);
    std::memcpy(message_.data() + sizeof header, done->image.rgb.data(), done->image.rgb.size());
    MPI_Isend(message_.data(), static_cast<int>(message_.size()), MPI_BYTE, 0, kTagSceneResult, MPI_COMM_WORLD,
              &pending_);
    return true;
  }

  SceneRenderThread renderer_;
  std::size_t left_ = 0;  // frames of the scene being rendered not yet sent
  bool ended_ = false;
  int code_ = kExitOk;
  Clock::time_point lastFromZero_ = Clock::now();
  Bytes message_;
  MPI_Request pending_ = MPI_REQUEST_NULL;
};

}  // namespace

int workOnScenes(int rank, ThreadPool& pool) {
  SceneWorker worker(pool);
  return worker.run(rank);
}

}  // namespace rayview::cluster
