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

  // Why a rank traces no more: it fell silent holding tiles (died, or stopped), mid-message, said it cannot trace
  // the scene, or the scene is too large to send.
  enum class Loss : int { None = 0, Silent, SilentMidMessage, CannotTrace, SceneTooLarge };

 private:
  class Pass;
  void ship(const TracedImage& image, std::uint64_t generation);
  void sendTo(int worker, int tag, std::vector<std::uint8_t> bytes);
  void sendToAll(int tag, std::vector<std::uint8_t> bytes);

  using Clock = std::chrono::steady_clock;
  bool lost(int rank) const { return lost_[rank].load() != static_cast<int>(Loss::None); }
  void markLost(int rank, Loss why);
  void settleOwed();
  // A rank that has owed an answer for longer than `patience`: dealt nothing new, and its tiles dealt again to the
  // others once none is left to deal, so that a dead rank costs a pass little (it is left out after kLostAfter).
  bool suspect(int rank, Clock::time_point now, Clock::duration patience) const {
    return owedSince_[rank] && now - *owedSince_[rank] > patience;
  }

  int ranks_;
  ThreadPool pool_;  // rank 0's own share of each pass
  // Per rank: why it is dealt no more tiles (Loss). Atomic: the viewer's stats read them while a pass runs.
  std::unique_ptr<std::atomic<int>[]> lost_;
  // Per rank: since when it has owed an answer (it holds tiles and has said nothing since); nullopt: it owes none.
  // Kept from pass to pass, so that a rank that died between two passes is waited for once, not at every pass.
  std::vector<std::optional<Clock::time_point>> owedSince_;
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
