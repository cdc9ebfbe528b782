#pragma once
// The viewer as rank 0 of an MPI job: the other ranks trace its passes. Rank 0 ships its scene's geometry to them
// once per scene (and traversal), a parameter snapshot per edit, and deals each pass's tiles to them and to its own
// threads; the progressive renderer puts the pixels together exactly as it does in one process. MPI is called
// only from the thread that calls renderPass (the renderer's controller) and, once it has ended, from the one
// that calls shutdown(): MPI_THREAD_SERIALIZED.

#include <atomic>
#include <chrono>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "mpi_outbox.h"
#include "rayview/cluster.h"
#include "rayview/pass_farm.h"
#include "rayview/prepared_scene.h"
#include "rayview/thread_pool.h"
#include "worker_watch.h"

namespace rayview::cluster {

class ViewerFarm final : public ViewerPassFarm {
 public:
  ViewerFarm(int ranks, int threads);
  ~ViewerFarm() override;

  bool accepts(const PixelSource& source) const override;
  bool renderPass(const PixelSource& source, const FarmPass& pass, const FarmSink& sink,
                  const std::function<bool()>& stopped, RayCounts& rays) override;

  // Tells every worker to end and waits (a few seconds at most) until each has said goodbye. Call once the
  // viewer, and with it the renderer's controller thread, is gone.
  void shutdown() override;

  std::string describe() const override;
  std::vector<std::string> lostRanks() const override;
  int ranks() const { return ranks_; }

  // Why a rank traces no more (its WorkerWatch::loss): it fell silent holding tiles (died, or stopped),
  // mid-message, said it cannot trace the scene, or the scene is too large to send.
  enum class Loss : int { None = WorkerWatch::kNotLost, Silent = WorkerWatch::kSilent, SilentMidMessage, CannotTrace,
                          SceneTooLarge };

 private:
  class Pass;
  void ship(const TracedImage& image, std::uint64_t generation);
  void sendTo(int worker, int tag, std::vector<std::uint8_t> bytes);
  void sendToAll(int tag, std::vector<std::uint8_t> bytes);

  using Clock = std::chrono::steady_clock;
  bool lost(int rank) const { return watch_.lost(rank); }
  Loss loss(int rank) const { return static_cast<Loss>(watch_.loss(rank)); }
  void settleOwed();

  int ranks_;
  ThreadPool pool_;  // rank 0's own share of each pass
  // Per rank: why it is dealt no more tiles (Loss; the viewer's stats read it while a pass runs) and since when it
  // has owed an answer. Kept from pass to pass, so that a rank that died between two passes is waited for once, not
  // at every pass.
  WorkerWatch watch_;
  // Per rank: tiles whose pixels were used. Atomic: the viewer's stats read them while a pass runs.
  std::unique_ptr<std::atomic<std::size_t>[]> tilesTraced_;
  std::unique_ptr<std::atomic<std::uint64_t>[]> busyMicroseconds_;  // per rank: time spent tracing them
  std::shared_ptr<const PreparedGeometry> shippedGeometry_;
  std::uint64_t geometrySerial_ = 0;
  std::uint64_t shippedGeneration_ = 0;
  std::uint64_t passSerial_ = 0;
  Outbox outbox_{[this](int rank) { return lost(rank); }};
  bool ended_ = false;
};

}  // namespace rayview::cluster
