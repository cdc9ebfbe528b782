// The viewer's speed-vs-accuracy measurement: started after the frame's edits are committed, run by the
// TradeoffTask on its own threads while the progressive renderer is stopped, cancelled by any edit or load.
#include <algorithm>
#include <cstdio>
#include <utility>

#include <imgui.h>

#include "tradeoff_advice.h"
#include "viewer_app.h"

namespace rayview {

void ViewerApp::measureTradeoff(double resolutionScale) {
  // Started in drawFrame() once this frame's edits are committed, so it measures what is about to be rendered.
  requestedTradeoff_ = resolutionScale;
  tradeoffError_.clear();
  tradeoffPanel_.message.clear();
}

TradeoffState ViewerApp::tradeoffState() const {
  TradeoffState state;
  state.running = measuring() || revealFrames_ > 0;  // done once the result is on screen
  state.error = tradeoffError_;
  if (tradeoffPanel_.report) state.points = static_cast<int>(tradeoffPanel_.report->points.size());
  return state;
}

std::string ViewerApp::whyNoTradeoff() const {
  if (!session_) return "no scene yet";
  if (loading()) return "a scene is loading";
  if (!editProblem_.empty()) return "the edits cannot be rendered";
  return {};
}

void ViewerApp::startRequestedTradeoff(const Layout& l) {
  if (!requestedTradeoff_) return;
  const double scale = *std::exchange(requestedTradeoff_, std::nullopt);
  if (const std::string why = whyNoTradeoff(); !why.empty()) {
    tradeoffError_ = "cannot measure: " + why;
    tradeoffPanel_.message = tradeoffError_;
    return;
  }
  TradeoffRequest request = tradeoffRequestFor(*session_, scale);
  // A quick look, not a benchmark: a run slowed by other processes is repeated once, not up to five times with
  // growing pauses (which can turn seconds into a minute on a busy machine); the notes still count them.
  request.options.slowedRetries = kViewerSlowedRetries;
  // Plotted to fit the image area (in screen units: the plot's text is sized in pixels, and a high-DPI screen
  // enlarges it crisply with nearest filtering), at most at the bench's size, with the bench's aspect.
  const ImGuiStyle& style = ImGui::GetStyle();
  const float margin = style.WindowPadding.x;
  const float room = std::min(l.viewWidth - 2.0f * margin - 2.0f * style.WindowPadding.x,
                              (l.viewHeight - 2.0f * margin - 2.0f * style.WindowPadding.y - ImGui::GetFrameHeight()) *
                                  kDefaultPlotWidth / kDefaultPlotHeight);
  request.plotWidth = std::clamp(static_cast<int>(room), kMinPlotWidth, kDefaultPlotWidth);
  request.plotHeight = request.plotWidth * kDefaultPlotHeight / kDefaultPlotWidth;

  restartRender(nullptr);  // the measurement gets the cores; the image on screen stays
  awaitedTradeoff_ = tradeoff_.start(std::move(request));
  measuredSerial_ = sceneSerial_;
  measuredCommit_ = session_->commitCount();
  tradeoffPanel_.running = true;
  tradeoffPanel_.progress = {};
  tradeoffPanel_.fraction = 0.0;
}

bool ViewerApp::pollTradeoff() {
  tradeoffPanel_.stale = session_ && tradeoffPanel_.report &&
                         (sceneSerial_ != measuredSerial_ || session_->commitCount() != measuredCommit_);
  if (awaitedTradeoff_ == 0) return false;
  const TradeoffStatus status = tradeoff_.status();
  tradeoffPanel_.progress = status.progress;
  tradeoffPanel_.fraction = status.fraction();
  std::optional<TradeoffResult> result = tradeoff_.takeResult();
  if (!result || result->id != awaitedTradeoff_) return false;  // the progress bar is redrawn while measuring

  awaitedTradeoff_ = 0;
  tradeoffPanel_.running = false;
  if (result->ok()) {
    plotTexture_.update(result->plot, ++plotVersion_);
    tradeoffPanel_.report = std::move(result->report);
    tradeoffPanel_.stale = false;
    tradeoffPanel_.reveal = true;
    tradeoffPanel_.showPlot = true;
    revealFrames_ = kRevealFrames;
    tradeoffError_.clear();
  } else {
    tradeoffError_ = result->cancelled ? "cancelled" : "failed: " + result->error;
    tradeoffPanel_.message = "Measurement " + tradeoffError_ + ".";
    if (!result->error.empty())
      std::fprintf(stderr, "rayview: measuring the trade failed: %s\n", result->error.c_str());
  }
  if (session_) restartRender(session_->currentSource());
  return true;
}

std::string ViewerApp::applyTradeoff(const Knob* knob, int value) {
  if (!session_) return "no scene is loaded";
  if (!tradeoffPanel_.report) return "nothing has been measured";
  const TradeoffReport& report = *tradeoffPanel_.report;
  const TradeoffPoint* row = knob ? findTradeoffRow(report, *knob, value) : tradeoffSuggestion(report);
  if (!row && knob) return "the measurement has no row " + std::string(knob->name) + " " + knob->format(value);
  if (!row) return "the advice suggests no setting: " + tradeoffAdvice(report);
  applyTradeoffRow(static_cast<std::size_t>(row - report.points.data()));
  return {};
}

void ViewerApp::applyTradeoffRow(std::size_t index) {
  if (!session_ || !tradeoffPanel_.report || index >= tradeoffPanel_.report->points.size()) return;
  const KnobSetting& setting = tradeoffPanel_.report->points[index].setting;
  // The same setter as the Render panel's widget: this frame's commit restarts the render, as one undo step.
  if (!applyKnobSetting(*session_, setting)) return;
  std::printf("tradeoff applied %s\n", describeRow(setting).c_str());
  std::fflush(stdout);
}

void ViewerApp::stopTradeoff(const std::string& why, bool restart) {
  if (!measuring()) return;
  const bool wasRunning = awaitedTradeoff_ != 0;
  tradeoff_.cancel();
  requestedTradeoff_.reset();
  awaitedTradeoff_ = 0;
  tradeoffPanel_.running = false;
  tradeoffError_ = why;
  tradeoffPanel_.message = "Measurement " + why + ".";
  if (restart && wasRunning && session_) restartRender(session_->currentSource());
}

}  // namespace rayview
