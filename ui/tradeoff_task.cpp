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
