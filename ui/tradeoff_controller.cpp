// The viewer's speed-vs-accuracy measurement: start, progress, result, cancel and Apply.
#include "tradeoff_controller.h"

#include <algorithm>
#include <cstdio>
#include <utility>

#include <GLFW/glfw3.h>
#include <imgui.h>

#include "tradeoff_advice.h"

namespace rayview {

TradeoffController::TradeoffController(int threads) : task_(threads) {
  task_.setFinishedListener([] { glfwPostEmptyEvent(); });
}

void TradeoffController::request(double resolutionScale) {
  requested_ = resolutionScale;
  error_.clear();
  panel_.message.clear();
}

TradeoffState TradeoffController::state() const {
  TradeoffState state;
  state.running = measuring() || revealFrames_ > 0;  // done once the result is on screen
  state.error = error_;
  if (panel_.report) state.points = static_cast<int>(panel_.report->points.size());
  return state;
}

bool TradeoffController::startRequested(const SceneSession* session, const std::string& whyNot,
                                         std::uint64_t sceneSerial, float viewWidth, float viewHeight) {
  if (!requested_) return false;
  const double scale = *std::exchange(requested_, std::nullopt);
  if (!whyNot.empty() || !session) {
    error_ = "cannot measure: " + (whyNot.empty() ? std::string("no scene yet") : whyNot);
    panel_.message = error_;
    return false;
  }
  TradeoffRequest request = tradeoffRequestFor(*session, scale);
  // A quick look, not a benchmark: a run slowed by other processes is repeated once, not up to five times with
  // growing pauses (which can turn seconds into a minute on a busy machine); the notes still count them.
  request.options.slowedRetries = kViewerSlowedRetries;
  // Plotted to fit the image area (in screen units: the plot's text is sized in pixels, and a high-DPI screen
  // enlarges it crisply with nearest filtering), at most at the bench's size, with the bench's aspect.
  const ImGuiStyle& style = ImGui::GetStyle();
  const float margin = style.WindowPadding.x;
  const float room = std::min(viewWidth - 2.0f * margin - 2.0f * style.WindowPadding.x,
                              (viewHeight - 2.0f * margin - 2.0f * style.WindowPadding.y - ImGui::GetFrameHeight()) *
                                  kDefaultPlotWidth / kDefaultPlotHeight);
  request.plotWidth = std::clamp(static_cast<int>(room), kMinPlotWidth, kDefaultPlotWidth);
  request.plotHeight = request.plotWidth * kDefaultPlotHeight / kDefaultPlotWidth;

  awaited_ = task_.start(std::move(request));
  measuredSerial_ = sceneSerial;
  measuredCommit_ = session->commitCount();
  panel_.running = true;
  panel_.progress = {};
  panel_.fraction = 0.0;
  return true;
}

bool TradeoffController::poll(const SceneSession* session, std::uint64_t sceneSerial) {
  panel_.stale =
      session && panel_.report && (sceneSerial != measuredSerial_ || session->commitCount() != measuredCommit_);
  if (awaited_ == 0) return false;
  const TradeoffStatus status = task_.status();
  panel_.progress = status.progress;
  panel_.fraction = status.fraction();
  std::optional<TradeoffResult> result = task_.takeResult();
  if (!result || result->id != awaited_) return false;  // the progress bar is redrawn while measuring

  awaited_ = 0;
  panel_.running = false;
  if (result->ok()) {
    plotTexture_.update(result->plot, ++plotVersion_);
    panel_.report = std::move(result->report);
    panel_.stale = false;
    panel_.reveal = true;
    panel_.showPlot = true;
    revealFrames_ = kRevealFrames;
    error_.clear();
  } else {
    error_ = result->cancelled ? "cancelled" : "failed: " + result->error;
    panel_.message = "Measurement " + error_ + ".";
    if (!result->error.empty()) std::fprintf(stderr, "rayview: measuring the trade failed: %s\n", result->error.c_str());
  }
  return true;
}

bool TradeoffController::stop(const std::string& why) {
  if (!measuring()) return false;
  const bool wasRunning = awaited_ != 0;
  task_.cancel();
  requested_.reset();
  awaited_ = 0;
  panel_.running = false;
  error_ = why;
  panel_.message = "Measurement " + why + ".";
  return wasRunning;
}

std::string TradeoffController::apply(SceneSession* session, const Knob* knob, int value) {
  if (!session) return "no scene is loaded";
  if (!panel_.report) return "nothing has been measured";
  const TradeoffReport& report = *panel_.report;
  const TradeoffPoint* row = knob ? findTradeoffRow(report, *knob, value) : tradeoffSuggestion(report);
  if (!row && knob) return "the measurement has no row " + std::string(knob->name) + " " + knob->format(value);
  if (!row) return "the advice suggests no setting: " + tradeoffAdvice(report);
  applyRow(session, static_cast<std::size_t>(row - report.points.data()));
  return {};
}

void TradeoffController::applyRow(SceneSession* session, std::size_t index) {
  if (!session || !panel_.report || index >= panel_.report->points.size()) return;
  const KnobSetting& setting = panel_.report->points[index].setting;
  // The same setter as the Render panel's widget: this frame's commit restarts the render, as one undo step.
  if (!applyKnobSetting(*session, setting)) return;
  std::printf("tradeoff applied %s\n", describeRow(setting).c_str());
  std::fflush(stdout);
}

}  // namespace rayview
