#pragma once
// Measuring the speed-for-accuracy trade of the scene on screen (docs/tradeoff.md) off the
// UI thread: one persistent worker thread (RequestWorker) runs measureTradeoff() on a thread pool of its own (created at the
// first measurement, then kept), one request at a time. No GL here.
//
// The UI pauses its progressive renderer while a measurement runs (so the two do not compete for the cores
// and the times mean something) and cancels the measurement on any edit or load.

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>

#include "rayview/image.h"
#include "rayview/plot.h"
#include "rayview/thread_pool.h"
#include "rayview/tradeoff.h"
#include "request_worker.h"

namespace rayview {

struct TradeoffRequest {
  std::shared_ptr<const SceneGeometry> geometry;  // the loaded scene's (shared, never copied)
  SceneParameters parameters;                     // what is rendered: the committed edits
  std::string sceneName;                          // the file's stem ("default" for the embedded scene)
  TradeoffOptions options;
  int plotWidth = kDefaultPlotWidth, plotHeight = kDefaultPlotHeight;  // pixels of the plot
};

// What the viewer measures: the committed edits, on the session's geometry (shared), at `scale` of the
// image's resolution; every knob is varied from the committed settings (what the user has on screen).
class SceneSession;
TradeoffRequest tradeoffRequestFor(const SceneSession& session, double scale);

// The side measured at `scale` of `pixels`, as measureTradeoff rounds it.
int scaledSide(int pixels, double scale);

struct TradeoffResult {
  std::uint64_t id = 0;
  bool cancelled = false;
  std::string error;  // why it failed ("" when it did not)
  TradeoffReport report;
  Image plot;         // plotTradeoff(report), when it neither failed nor was cancelled
  bool ok() const { return !cancelled && error.empty(); }
};

struct TradeoffStatus {
  bool busy = false;
  TradeoffProgress progress;
  double fraction() const {
    if (progress.rendersPlanned <= 0) return 0.0;
    return std::min(1.0, static_cast<double>(progress.rendersDone) / progress.rendersPlanned);
  }
};

class TradeoffTask {
 public:
  explicit TradeoffTask(int threads);  // of the measuring pool; <= 0: one per hardware thread

  // Called on the worker when a result is ready (the viewer wakes its UI loop). Set it before start().
  void setFinishedListener(std::function<void()> listener) { worker_.setFinishedListener(std::move(listener)); }

  // Returns at once with the request's id. Cancels a measurement still running.
  std::uint64_t start(TradeoffRequest request) { return worker_.submit(std::move(request)); }
  // Stops the running measurement within one tile; its result, if any, says cancelled. Returns at once.
  void cancel() { worker_.cancel(); }

  // The result of the newest request, once, when it is ready.
  std::optional<TradeoffResult> takeResult() { return worker_.take(); }
  TradeoffStatus status() const;

 private:
  TradeoffResult run(std::uint64_t id, const TradeoffRequest& request, const std::atomic<bool>& cancel);

  const int threads_;
  std::unique_ptr<ThreadPool> pool_;  // made by the worker at its first measurement, then kept
  mutable std::mutex progressMutex_;
  TradeoffProgress progress_;         // guarded by progressMutex_
  RequestWorker<TradeoffRequest, TradeoffResult> worker_;  // last: its thread uses the members above
};

}  // namespace rayview
