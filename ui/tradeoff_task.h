#pragma once
// Measuring the speed-for-accuracy trade of the scene on screen (issue 4, item 2; docs/tradeoff.md) off the
// UI thread: one persistent worker thread runs measureTradeoff() on a thread pool of its own (created at the
// first measurement, then kept), one request at a time. No GL here.
//
// The UI pauses its progressive renderer while a measurement runs (so the two do not compete for the cores
// and the times mean something) and cancels the measurement on any edit or load.

#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

#include "rayview/image.h"
#include "rayview/plot.h"
#include "rayview/thread_pool.h"
#include "rayview/tradeoff.h"
#include "scene_edits.h"

namespace rayview {

struct TradeoffRequest {
  std::shared_ptr<const Scene> source;  // the loaded scene, meshes included (never copied on the UI thread)
  SceneEdits edits;                     // what is rendered: camera, lights, materials, depth, background
  TradeoffOptions options;
  int plotWidth = kDefaultPlotWidth, plotHeight = kDefaultPlotHeight;  // pixels of the plot
};

// The scene measured: a copy of `source` (meshes included) with `edits` applied. Runs on the worker.
std::shared_ptr<const Scene> measuringScene(const Scene& source, const SceneEdits& edits);

// The side measured at `scale` of `pixels`, as measureTradeoff rounds it.
int scaledSide(int pixels, double scale);

// One line of advice from a finished report: the fastest setting that keeps all but kAdvicePctOff % of the
// pixels within 1 of the best image, with the best image's time and the defaults' (the baseline: every knob at
// its default) for comparison. "" without the reference and the baseline among the points.
inline constexpr double kAdvicePctOff = 1.0;
std::string tradeoffAdvice(const TradeoffReport& report);

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
  ~TradeoffTask();
  TradeoffTask(const TradeoffTask&) = delete;
  TradeoffTask& operator=(const TradeoffTask&) = delete;

  // Called on the worker when a result is ready (the viewer wakes its UI loop). Set it before start().
  void setFinishedListener(std::function<void()> listener);

  // Returns at once with the request's id. Cancels a measurement still running.
  std::uint64_t start(TradeoffRequest request);
  // Stops the running measurement within one tile; its result, if any, says cancelled. Returns at once.
  void cancel();

  // The result of the newest request, once, when it is ready.
  std::optional<TradeoffResult> takeResult();
  TradeoffStatus status() const;

 private:
  void workerLoop();
  TradeoffResult run(std::uint64_t id, const TradeoffRequest& request);

  const int threads_;
  std::unique_ptr<ThreadPool> pool_;  // worker thread only
  std::function<void()> listener_;

  mutable std::mutex mutex_;
  std::condition_variable wake_;
  std::optional<TradeoffRequest> pending_;  // guarded by mutex_
  std::uint64_t pendingId_ = 0;             // guarded by mutex_
  bool running_ = false;                    // guarded by mutex_
  TradeoffProgress progress_;               // guarded by mutex_
  std::optional<TradeoffResult> result_;    // guarded by mutex_
  bool stopping_ = false;                   // guarded by mutex_

  std::atomic<bool> cancel_{false};  // raised for the running measurement; lowered when the next one starts
  std::thread worker_;
};

}  // namespace rayview
