#pragma once
// Runs an automation script from the UI loop: at most one command per UI frame, and a waiting command
// (wait-final, open, sleep, wait-frames, measure-tradeoff, compare) holds the script until its condition is met or its
// time is up.
// The viewer is reached only through ScriptHost, the same operations its keys and panels use.

#include <chrono>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>

#include "rayview/model_options.h"
#include "automation_script.h"
#include "display_mapping.h"
#include "rayview/image_metrics.h"

namespace rayview {

class SceneSession;
struct Knob;

// The newest speed-vs-accuracy measurement, as a script sees it.
struct TradeoffState {
  bool running = false;  // requested or measuring
  int points = 0;        // of the finished report
  std::string error;     // why it has no report ("cancelled: ...", a failure); "" when it has one
};

class ScriptHost {
 public:
  virtual ~ScriptHost() = default;
  virtual SceneSession* session() = 0;  // null until a scene has loaded
  virtual void open(const std::string& path) = 0;
  virtual void reload() = 0;
  // Which axis of a model points up (--up): a model on screen is read again with it.
  virtual void setModelUp(ModelUpAxis up) = 0;
  virtual bool loading() const = 0;
  virtual std::string loadError() const = 0;  // what the error panel shows ("" when nothing)
  virtual std::string scenePath() const = 0;  // the scene on screen ("" for the embedded default)
  virtual std::uint64_t sceneSerial() const = 0;  // increases whenever another scene (or reload) goes on screen
  // The final pass of the current edits is on screen and nothing is pending.
  virtual bool finalFrameShown() const = 0;
  virtual std::string editProblem() const = 0;  // why the current edits are not rendered ("" when they are)
  // The image a frame save writes (the file's resolution, `rayview render`'s image) is ready: in the image view
  // the final pass on screen; in the window view a background render of the file's image, which this starts when
  // the final pass is on screen and it has not yet been made for these edits.
  virtual bool fileImageReady() = 0;
  // That image, raw (as `rayview render` writes it) or as displayed. "" = numbered; throws on failure (also
  // when it is not ready).
  virtual std::filesystem::path saveFrame(const std::string& path, FrameSave what) = 0;
  // The window view (the image area's pixels, the file's view extended) or the image view (the file's image).
  virtual void setImageView(bool imageView) = 0;
  virtual std::filesystem::path saveScene(const std::string& path) = 0;  // "" = numbered; throws on failure
  virtual void screenshot(const std::string& path) = 0;  // taken when this frame has been drawn
  // The image area as seen, without panels and overlays, when this frame has been drawn ("": numbered).
  virtual void saveView(const std::string& path) = 0;
  // The newest screenshot or view save asked for: nullopt while it is still to be taken, "" when it was written,
  // else why not (which fails the script).
  virtual std::optional<std::string> captureOutcome() const { return std::string(); }
  virtual std::string stateLine() const = 0;
  virtual void resizeWindow(int width, int height) = 0;
  // Measure the speed-for-accuracy trade of the scene on screen at this share of its resolution (the render
  // pauses meanwhile); cancel it; what became of it.
  virtual void measureTradeoff(double resolutionScale) = 0;
  virtual void cancelTradeoff() = 0;
  virtual TradeoffState tradeoffState() const = 0;
  // Compare with a reference image: load it ("" when it loaded, otherwise why not, naming the file); the figures
  // of the final pass on screen against it, once they are computed; why there can be none ("" while there may be).
  virtual std::string loadReference(const std::string& path) = 0;
  virtual std::optional<ImageError> finalComparison() const = 0;
  virtual std::string comparisonProblem() const = 0;
  // Exposure and gamma: how the image area shows the image. Setting them never restarts the render.
  virtual DisplayMapping displayMapping() const = 0;
  virtual void setDisplayMapping(const DisplayMapping& mapping) = 0;
  // Apply a row of the last result, as its Apply button does: the row setting `knob` to `value`, or (knob
  // null) the setting the advice suggests. "" when applied, else why not.
  virtual std::string applyTradeoff(const Knob* knob, int value) = 0;
  virtual void quit(int exitCode) = 0;
  // The unsaved edits a viewer that stopped left for this scene: restore them, or discard them ("" when done, else
  // why not: none offered, or they no longer fit the scene).
  virtual std::string answerRecovery(bool) { return "no recovered edits are offered"; }
};

class ScriptRunner {
 public:
  explicit ScriptRunner(Script script) : script_(std::move(script)) {}

  // Runs the next command if the previous one is done. Call once per UI frame.
  void step(ScriptHost& host);

  // True until the last command has finished (including its wait) or one has failed.
  bool running() const { return !failed() && (next_ < script_.commands.size() || wait_ != Wait::None); }
  bool failed() const { return !failure_.empty(); }
  const std::string& failure() const { return failure_; }  // "FILE:LINE: message"

 private:
  using Clock = std::chrono::steady_clock;
  enum class Wait { None, Final, Load, Frames, Until, Tradeoff, SaveFrame, Compare, Capture };

  void start(const ScriptCommand& command, ScriptHost& host);
  bool waitIsOver(ScriptHost& host);
  void fail(const std::string& message);
  void applySet(const ScriptCommand& command, ScriptHost& host);
  void applyCamera(const ScriptCommand& command, ScriptHost& host);
  void checkExpectedError(const ScriptCommand& command, ScriptHost& host);

  Script script_;
  std::size_t next_ = 0;
  const ScriptCommand* current_ = nullptr;
  Wait wait_ = Wait::None;
  Clock::time_point deadline_{};
  std::uint64_t framesLeft_ = 0;
  std::string pathBeforeOpen_;
  std::uint64_t serialBeforeOpen_ = 0;
  bool initialLoadSeen_ = false;
  std::string failure_;
};

}  // namespace rayview
