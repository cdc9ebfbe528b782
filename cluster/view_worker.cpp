// A worker of the viewer under MPI: holds the geometry and the newest parameter snapshot rank 0 sent, traces the
// tiles it is dealt, and drops those of a generation an edit has replaced.
#include <mpi.h>

#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <deque>
#include <exception>
#include <memory>
#include <new>
#include <string>
#include <thread>
#include <vector>

#include "rayview/cluster.h"
#include "rayview/exit_codes.h"
#include "mpi_link.h"
#include "mpi_outbox.h"
#include "rayview/grid_render.h"
#include "rayview/pass_farm.h"
#include "rayview/pixel_source.h"
#include "rayview/prepared_scene.h"
#include "rayview/thread_pool.h"
#include "view_codec.h"
#include "tile_exchange.h"
#include "view_messages.h"

namespace rayview::cluster {
namespace {

using Clock = std::chrono::steady_clock;

// While the window shows a finished image, a worker looks for work this often: a fraction of a percent of a core.
constexpr auto kIdlePause = std::chrono::milliseconds(5);

class ViewWorker {
 public:
  explicit ViewWorker(int threads) : pool_(threads) {}

  int run() {
    auto pause = kProbePause;
    for (;;) {
      if (!readMessages()) break;
      if (traceNext()) {
        pause = kProbePause;
        continue;
      }
      outbox_.reap();
      std::this_thread::sleep_for(pause);
      pause = std::min<std::chrono::microseconds>(pause * 2, kIdlePause);
    }
    send(kTagViewBye, {});
    outbox_.drain(std::chrono::seconds(5));
    return kExitOk;
  }

 private:
  // Every message waiting, in the order rank 0 sent them. False once rank 0 said the window closed.
  bool readMessages() {
    MPI_Status status;
    while (messageWaiting(0, MPI_ANY_TAG, status)) {
      int bytes = 0;
      MPI_Get_count(&status, MPI_BYTE, &bytes);
      inbox_.resize(static_cast<std::size_t>(bytes) + 1);
      MPI_Recv(inbox_.data(), bytes, MPI_BYTE, 0, status.MPI_TAG, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
      const auto size = static_cast<std::size_t>(bytes);
      try {
        if (status.MPI_TAG == kTagViewQuit) {
          if (size >= 1 && inbox_[0] != 0) notePeerLost();  // MPI_Finalize would wait for the lost rank
          return false;
        }
        if (status.MPI_TAG == kTagViewGeometry) takeGeometry(size);
        if (status.MPI_TAG == kTagViewSnapshot) takeSnapshot(size);
        if (status.MPI_TAG == kTagViewTile && size == sizeof(ViewTileRequest)) {
          ViewTileRequest request;
          std::memcpy(&request, inbox_.data(), sizeof request);
          queue_.push_back(request);
        }
      } catch (const CodecError& error) {
        problem(error.what());
      } catch (const std::bad_alloc&) {
        problem("out of memory");
      }
    }
    return true;
  }

  void takeGeometry(std::size_t size) {
    image_.reset();
    geometry_.reset();  // the old scene's memory goes before the new one is built
    if (size < sizeof(std::uint64_t)) throw CodecError("truncated");
    std::memcpy(&geometrySerial_, inbox_.data(), sizeof geometrySerial_);
    ShippedGeometry shipped = decodeGeometry(inbox_.data() + sizeof geometrySerial_, size - sizeof geometrySerial_);
    std::shared_ptr<const SceneGeometry> geometry(std::move(shipped.geometry));
    std::shared_ptr<const PreparedGeometry> prepared;
    std::exception_ptr failure;
    whileAlive([&] {
      try {
        prepared = prepareGeometry(geometry, shipped.origin, shipped.accel, BvhBuild::Interactive, nullptr, nullptr,
                                   shipped.parameters ? &*shipped.parameters : nullptr);
      } catch (...) {
        failure = std::current_exception();  // rethrown here, where a std::bad_alloc is reported to rank 0
      }
    });
    if (failure) std::rethrow_exception(failure);
    geometry_ = std::move(prepared);
  }

  void takeSnapshot(std::size_t size) {
    ViewSnapshotHeader header;
    if (size < sizeof header) throw CodecError("truncated");
    std::memcpy(&header, inbox_.data(), sizeof header);
    generation_ = header.generation;
    image_.reset();
    Snapshot snapshot = decodeSnapshot(inbox_.data() + sizeof header, size - sizeof header);
    if (!geometry_ || header.geometry != geometrySerial_) throw CodecError("a snapshot without its geometry");
    image_ = std::make_shared<TracedImage>(std::make_shared<const SceneParameters>(std::move(snapshot.parameters)),
                                           geometry_, snapshot.settings);
  }

  // Traces the oldest tile of the current generation; tiles of replaced generations are dropped unread.
  bool traceNext() {
    bool dropped = false;
    while (!queue_.empty() && (queue_.front().generation != generation_ || !image_)) {
      queue_.pop_front();
      dropped = true;
    }
    // Rank 0 counts them as owed until it hears from this rank: a word says they will not come.
    if (dropped) send(kTagViewAlive, {});
    if (queue_.empty()) return false;
    const ViewTileRequest request = queue_.front();
    queue_.pop_front();
    const auto start = Clock::now();
    gridTilePixels({request.x0, request.y0, request.x1, request.y1}, request.stride, request.skipStride, pixels_);
    RayCounts rays;
    whileAlive([&] { traceColors(farmTrace(*image_, request.sample), pixels_, pool_, colors_, rays); });
    ViewTileResultHeader header{request.pass, request.tile, static_cast<std::int32_t>(pixels_.size()),
                                std::chrono::duration<double, std::milli>(Clock::now() - start).count(),
                                rays.camera, rays.shadow, rays.reflection};
    std::vector<std::uint8_t> message(sizeof header + colors_.size() * sizeof(Color));
    std::memcpy(message.data(), &header, sizeof header);
    // A tile may hold no pixel of the pass (all on the coarser grid), and memcpy must not see a null pointer.
    if (!colors_.empty()) std::memcpy(message.data() + sizeof header, colors_.data(), colors_.size() * sizeof(Color));
    send(kTagViewResult, std::move(message));
    return true;
  }

  // Runs `work` on a thread of its own while this one keeps MPI moving (a result larger than OpenMPI sends eagerly
  // reaches rank 0 only while its sender makes MPI calls) and tells rank 0 it is alive, however long the work.
  template <class Work>
  void whileAlive(Work&& work) {
    std::atomic<bool> done{false};
    std::thread worker([&] {
      work();
      done.store(true);
    });
    auto lastAlive = Clock::now();
    while (!done.load()) {
      outbox_.reap();
      if (Clock::now() - lastAlive > kAliveEvery) {
        send(kTagViewAlive, {});
        lastAlive = Clock::now();
      }
      std::this_thread::sleep_for(kProbePause);
    }
    worker.join();
  }

  void problem(const std::string& why) {
    if (reported_) return;
    reported_ = true;
    send(kTagViewProblem, std::vector<std::uint8_t>(why.begin(), why.end()));
  }

  void send(int tag, std::vector<std::uint8_t> bytes) { outbox_.send(0, tag, std::move(bytes)); }

  ThreadPool pool_;
  std::shared_ptr<const PreparedGeometry> geometry_;
  std::uint64_t geometrySerial_ = 0;
  std::shared_ptr<const TracedImage> image_;
  std::uint64_t generation_ = 0;
  std::deque<ViewTileRequest> queue_;
  Outbox outbox_;
  std::vector<std::uint8_t> inbox_;
  std::vector<PixelXY> pixels_;
  std::vector<Color> colors_;
  bool reported_ = false;
};

}  // namespace

int runViewWorker(int threads) {
  MPI_Comm_set_errhandler(MPI_COMM_WORLD, MPI_ERRORS_RETURN);
  ViewWorker worker(threads);
  return worker.run();
}

}  // namespace rayview::cluster
