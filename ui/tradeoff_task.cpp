#include "tradeoff_task.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <exception>
#include <utility>

namespace rayview {

std::shared_ptr<const Scene> measuringScene(const Scene& source, const SceneEdits& edits) {
  auto scene = std::make_shared<Scene>(source);
  applyEdits(edits, *scene);
  return scene;
}

int scaledSide(int pixels, double scale) {
  return std::max(1, static_cast<int>(std::lround(pixels * scale)));
}

std::string tradeoffAdvice(const TradeoffReport& report) {
  const TradeoffPoint* best = nullptr;
  const TradeoffPoint* defaults = nullptr;
  const TradeoffPoint* fastest = nullptr;
  for (const TradeoffPoint& p : report.points) {
    if (p.setting.knob == TradeoffKnob::Reference) best = &p;
    if (p.setting.knob == TradeoffKnob::Preview && p.setting.stride == 1) defaults = &p;
    if (p.setting.knob == TradeoffKnob::Reference || p.error.pctOffByMoreThan1 > kAdvicePctOff) continue;
    if (!fastest || p.timeMs < fastest->timeMs) fastest = &p;
  }
  if (!best || !defaults) return {};
  char line[320];
  if (!fastest) {
    std::snprintf(line, sizeof line,
                  "No setting but the best image (%.1f ms) has %g%% of pixels or fewer off by more than 1; the "
                  "defaults take %.1f ms with %.1f%% off.",
                  best->timeMs, kAdvicePctOff, defaults->timeMs, defaults->error.pctOffByMoreThan1);
  } else if (defaults->error.pctOffByMoreThan1 <= kAdvicePctOff && fastest->timeMs >= defaults->timeMs) {
    std::snprintf(line, sizeof line,
                  "The defaults are enough: %.1f ms with %.2f%% of pixels off by more than 1 (the best image: "
                  "%.1f ms).",
                  defaults->timeMs, defaults->error.pctOffByMoreThan1, best->timeMs);
  } else {
    std::snprintf(line, sizeof line,
                  "Fastest with %g%% of pixels or fewer off by more than 1: %s %s, %.1f ms (the best image: %.1f ms; "
                  "the defaults: %.1f ms with %.1f%% off).",
                  kAdvicePctOff, std::string(toString(fastest->setting.knob)).c_str(), fastest->setting.label.c_str(),
                  fastest->timeMs, best->timeMs, defaults->timeMs, defaults->error.pctOffByMoreThan1);
  }
  return line;
}

TradeoffTask::TradeoffTask(int threads) : threads_(threads), worker_([this] { workerLoop(); }) {}

TradeoffTask::~TradeoffTask() {
  {
    std::lock_guard lock(mutex_);
    stopping_ = true;
    cancel_ = true;
  }
  wake_.notify_all();
  worker_.join();
}

void TradeoffTask::setFinishedListener(std::function<void()> listener) {
  std::lock_guard lock(mutex_);
  listener_ = std::move(listener);
}

std::uint64_t TradeoffTask::start(TradeoffRequest request) {
  std::uint64_t id;
  {
    std::lock_guard lock(mutex_);
    id = ++pendingId_;
    pending_ = std::move(request);
    result_.reset();  // an older result not yet taken is stale now
    cancel_ = true;   // the running one, if any; lowered when the worker takes this request
  }
  wake_.notify_all();
  return id;
}

void TradeoffTask::cancel() {
  std::lock_guard lock(mutex_);
  pending_.reset();
  result_.reset();
  cancel_ = true;
}

std::optional<TradeoffResult> TradeoffTask::takeResult() {
  std::lock_guard lock(mutex_);
  return std::exchange(result_, std::nullopt);
}

TradeoffStatus TradeoffTask::status() const {
  std::lock_guard lock(mutex_);
  TradeoffStatus s;
  s.busy = running_ || pending_.has_value();
  s.progress = progress_;
  return s;
}

void TradeoffTask::workerLoop() {
  for (;;) {
    TradeoffRequest request;
    std::uint64_t id;
    {
      std::unique_lock lock(mutex_);
      wake_.wait(lock, [&] { return stopping_ || pending_.has_value(); });
      if (stopping_) break;
      request = std::move(*pending_);
      pending_.reset();
      id = pendingId_;
      running_ = true;
      progress_ = TradeoffProgress{0, 0, "copying the scene"};
      cancel_ = false;  // under the lock: a cancel() from now on reaches this run
    }
    TradeoffResult result = run(id, request);
    request = TradeoffRequest{};  // let go of the scene before reporting
    std::function<void()> listener;
    {
      std::lock_guard lock(mutex_);
      running_ = false;
      // Only the newest request's result is handed back, and a cancelled one only if nothing replaced it.
      if (id == pendingId_ && !pending_) result_ = std::move(result);
      listener = listener_;
    }
    if (listener) listener();
  }
  pool_.reset();
}

TradeoffResult TradeoffTask::run(std::uint64_t id, const TradeoffRequest& request) {
  TradeoffResult result;
  result.id = id;
  try {
    std::shared_ptr<const Scene> scene = measuringScene(*request.source, request.edits);
    if (!pool_) pool_ = std::make_unique<ThreadPool>(threads_);
    result.report = measureTradeoff(std::move(scene), request.options, *pool_, &cancel_,
                                    [this](const TradeoffProgress& progress) {
                                      std::lock_guard lock(mutex_);
                                      progress_ = progress;
                                    });
    result.cancelled = result.report.cancelled || cancel_.load();
    if (!result.cancelled) result.plot = plotTradeoff(result.report, request.plotWidth, request.plotHeight);
  } catch (const std::exception& error) {
    result.error = error.what();
  }
  return result;
}

}  // namespace rayview
