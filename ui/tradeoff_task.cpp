#include "tradeoff_task.h"

#include "scene_session.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <utility>

namespace rayview {

TradeoffRequest tradeoffRequestFor(const SceneSession& session, double scale) {
  TradeoffRequest request;
  request.geometry = session.geometry().source;  // shared: the meshes are never copied
  request.parameters = session.committedEdits();
  const std::filesystem::path& source = session.loaded().sourcePath;
  request.sceneName = source.empty() ? "default" : source.stem().string();
  request.options.resolutionScale = scale;
  request.options.baseline = session.committedSettings();
  return request;
}

int scaledSide(int pixels, double scale) {
  return std::max(1, static_cast<int>(std::lround(pixels * scale)));
}

std::string tradeoffAdvice(const TradeoffReport& report) {
  const TradeoffPoint* best = nullptr;
  const TradeoffPoint* yours = nullptr;  // the baseline: the user's settings
  const TradeoffPoint* fastest = nullptr;
  for (const TradeoffPoint& p : report.points) {
    if (p.setting.knob == TradeoffKnob::BestImage) best = &p;
    if (p.setting.knob == TradeoffKnob::Preview && p.setting.stride == 1) yours = &p;
    if (p.setting.knob == TradeoffKnob::BestImage || p.error.pctOffByMoreThan1 > kAdvicePctOff) continue;
    if (!fastest || p.timeMs < fastest->timeMs) fastest = &p;
  }
  if (!best || !yours) return {};
  char line[320];
  if (!fastest) {
    std::snprintf(line, sizeof line,
                  "No setting but the best image (%.1f ms) has %g%% of pixels or fewer off by more than 1; your "
                  "settings take %.1f ms with %.1f%% off.",
                  best->timeMs, kAdvicePctOff, yours->timeMs, yours->error.pctOffByMoreThan1);
  } else if (yours->error.pctOffByMoreThan1 <= kAdvicePctOff && fastest->timeMs >= yours->timeMs) {
    std::snprintf(line, sizeof line,
                  "Your settings are enough: %.1f ms with %.2f%% of pixels off by more than 1 (the best image: "
                  "%.1f ms).",
                  yours->timeMs, yours->error.pctOffByMoreThan1, best->timeMs);
  } else {
    std::snprintf(line, sizeof line,
                  "Fastest with %g%% of pixels or fewer off by more than 1: %s, %.1f ms (the best image: %.1f ms; "
                  "your settings: %.1f ms with %.1f%% off).",
                  kAdvicePctOff, describeRow(fastest->setting).c_str(), fastest->timeMs, best->timeMs, yours->timeMs,
                  yours->error.pctOffByMoreThan1);
  }
  return line;
}

TradeoffTask::TradeoffTask(int threads)
    : threads_(threads),
      worker_([this](std::uint64_t id, const TradeoffRequest& request, const std::atomic<bool>& cancel) {
        return run(id, request, cancel);
      }) {}

TradeoffStatus TradeoffTask::status() const {
  TradeoffStatus s;
  s.busy = worker_.busy();
  std::lock_guard lock(progressMutex_);
  s.progress = progress_;
  return s;
}

TradeoffResult TradeoffTask::run(std::uint64_t id, const TradeoffRequest& request, const std::atomic<bool>& cancel) {
  {
    std::lock_guard lock(progressMutex_);
    progress_ = TradeoffProgress{0, 0, "starting"};
  }
  TradeoffResult result;
  result.id = id;
  try {
    if (!pool_) pool_ = std::make_unique<ThreadPool>(threads_);
    result.report = measureTradeoff(request.parameters, request.geometry, request.sceneName, request.options, *pool_,
                                    &cancel, [this](const TradeoffProgress& progress) {
                                      std::lock_guard lock(progressMutex_);
                                      progress_ = progress;
                                    });
    result.cancelled = result.report.cancelled || cancel.load();
    if (!result.cancelled) result.plot = plotTradeoff(result.report, request.plotWidth, request.plotHeight);
  } catch (const std::exception& error) {
    result.error = error.what();
  }
  return result;
}

}  // namespace rayview
