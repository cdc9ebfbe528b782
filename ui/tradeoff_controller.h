#pragma once
// The viewer's speed-vs-accuracy measurement: asked for (panel, script), started once the frame's edits are
// committed, run by the TradeoffTask on its own threads while the caller keeps the progressive render stopped,
// cancelled by any edit or load; its result in the panel and the plot, and Apply.

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>

#include "image_texture.h"
#include "panels.h"
#include "script_runner.h"
#include "tradeoff_task.h"

namespace rayview {

// Retries of a run slowed by other processes (the bench's default is 5).
inline constexpr int kViewerSlowedRetries = 1;
// A new result opens its panel and scrolls to it; ImGui applies the scroll in the frame after: the result is on
// screen (for scripts: measure-tradeoff is over) after this many frames.
inline constexpr int kRevealFrames = 2;
inline constexpr int kMinPlotWidth = 480;  // narrower, the plot's labels overlap

class TradeoffController {
 public:
  explicit TradeoffController(int threads);  // of its own pool, made at the first measurement

  // Measure at this share of the resolution, once this frame's edits are committed (startRequested).
  void request(double resolutionScale);
  bool measuring() const { return requested_.has_value() || awaited_ != 0; }
  TradeoffState state() const;
  // Starts the measurement asked for, of `session` as committed, with a plot that fits an image area of this
  // size; `whyNot` non-empty refuses it. True when it started: the caller stops the render meanwhile.
  bool startRequested(const SceneSession* session, const std::string& whyNot, std::uint64_t sceneSerial,
                      float viewWidth, float viewHeight);
  // Takes the progress and the result: true when the measurement ended (done, failed or cancelled by the task):
  // the caller restarts the render. Also marks a result older than the scene on screen as stale.
  bool poll(const SceneSession* session, std::uint64_t sceneSerial);
  // Cancels what was asked or running, saying why; true when one was running (the render was stopped for it).
  bool stop(const std::string& why);
  // Apply: the row setting `knob` to `value` (knob null: the advice's suggestion) into the session, as the Render
  // panel's widget would; "" when applied, else why not.
  std::string apply(SceneSession* session, const Knob* knob, int value);
  void applyRow(SceneSession* session, std::size_t index);
  // A frame was drawn: a new result is on screen after kRevealFrames.
  void frameDrawn() {
    if (revealFrames_ > 0) --revealFrames_;
  }

  TradeoffPanelState& panel() { return panel_; }
  const ImageTexture& plot() const { return plotTexture_; }

 private:
  TradeoffTask task_;
  ImageTexture plotTexture_;
  TradeoffPanelState panel_;
  std::optional<double> requested_;  // started once this frame's edits are committed
  std::uint64_t awaited_ = 0;        // the running measurement's id
  std::uint64_t plotVersion_ = 0;
  std::uint64_t measuredSerial_ = 0, measuredCommit_ = 0;  // what the last measurement saw
  std::string error_;                                      // why the newest measurement has no report
  int revealFrames_ = 0;                                   // frames until a new result is on screen
};

}  // namespace rayview
