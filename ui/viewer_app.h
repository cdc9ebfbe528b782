#pragma once
// The viewer: one UI thread that sleeps until something happens, draws the newest complete pass and the
// panels, turns input into edits and edits into restarts. It never renders, never builds a BVH and never
// waits for either: the controllers' tasks do that on their own threads. ViewerApp wires the controllers
// (loading, rendering, comparing, the trade-off measurement, saving, the image view, the unsaved-edits question)
// to the window, the panels and the script host, and runs the frame loop.

#include <chrono>
#include <cstdint>
#include <optional>
#include <string>

#include "compare_controller.h"
#include "image_view_controller.h"
#include "imgui_layer.h"
#include "load_controller.h"
#include "navigation_input.h"
#include "recovery_controller.h"
#include "panels.h"
#include "render_controller.h"
#include "save_controller.h"
#include "script_runner.h"
#include "tradeoff_controller.h"
#include "unsaved_prompt.h"
#include "rayview/viewer.h"
#include "viewer_layout.h"
#include "window.h"

namespace rayview {

// Frame pacing (seconds): how long the UI sleeps in each state when nothing arrives.
// A pass in flight wakes the loop itself (the renderer's frame listener posts an empty event); this is
// only the fallback, and the rate at which a running script's conditions are checked.
inline constexpr double kRenderingPollSeconds = 1.0 / 120.0;
inline constexpr double kRenderingFallbackSeconds = 0.25;
inline constexpr double kLoadingPollSeconds = 1.0 / 30.0;     // progress bar
inline constexpr double kMeasuringPollSeconds = 0.1;          // progress bar, drawn seldom: the cores measure
inline constexpr double kIdleWaitSeconds = 10.0;              // final image, nothing to watch
// Frames drawn after the last event so ImGui's hover and focus state settles.
inline constexpr int kSettleFrames = 2;
// The panel column's width at content scale 1, and at most this share of the window.
inline constexpr float kPanelWidth = 400.0f;
inline constexpr float kMaxPanelShare = 0.45f;
inline constexpr int kInitialWindowWidth = 1280;
inline constexpr int kInitialWindowHeight = 800;
// The lights and the pivot stay in the view this long after a drag or a wheel notch.
inline constexpr std::chrono::milliseconds kMarksAfterNavigation{1500};

class ViewerApp final : public ScriptHost {
 public:
  // Throws DisplayUnavailable when no window can be opened.
  ViewerApp(const ViewerOptions& options, std::optional<Script> script);

  // Runs until the window closes, Ctrl+Q, or the script quits or fails. Returns the exit code.
  int run();

  // ScriptHost: what automation (and the keys and panels) can do.
  SceneSession* session() override { return load_.session(); }
  void open(const std::string& path) override;
  void reload() override;
  void setModelUp(ModelUpAxis up) override;
  bool loading() const override { return load_.loading(); }
  std::string loadError() const override { return load_.loadError(); }
  std::string scenePath() const override { return load_.scenePath(); }
  std::uint64_t sceneSerial() const override { return load_.sceneSerial(); }
  bool finalFrameShown() const override;
  std::string editProblem() const override { return editProblem_; }
  bool fileImageReady() override { return saves_.fileImageReady(frameSaveContext()); }
  std::filesystem::path saveFrame(const std::string& path, FrameSave what) override;
  void setImageView(bool imageView) override;
  std::filesystem::path saveScene(const std::string& path) override;
  void screenshot(const std::string& path) override { saves_.requestScreenshot(path); }
  void saveView(const std::string& path) override { saves_.requestViewSave(path); }
  std::optional<std::string> captureOutcome() const override { return saves_.captureOutcome(); }
  std::string stateLine() const override;
  void resizeWindow(int width, int height) override { window_.setSize(width, height); }
  void measureTradeoff(double resolutionScale) override { tradeoff_.request(resolutionScale); }
  void cancelTradeoff() override { stopTradeoff("cancelled", true); }
  TradeoffState tradeoffState() const override { return tradeoff_.state(); }
  std::string loadReference(const std::string& path) override;
  std::optional<ImageError> finalComparison() const override;
  std::string comparisonProblem() const override;
  DisplayMapping displayMapping() const override { return display_.mapping; }
  void setDisplayMapping(const DisplayMapping& mapping) override { display_.mapping = mapping; }
  std::string applyTradeoff(const Knob* knob, int value) override { return tradeoff_.apply(session(), knob, value); }
  void quit(int exitCode) override;
  std::string answerRecovery(bool restore) override;

 private:
  using Clock = std::chrono::steady_clock;

  // What the background tasks brought since the last frame; true when something changed.
  bool pollTasks(Clock::time_point now);
  bool takeNewFrame();
  void onLoad(const LoadEvent& event);
  void commitEdits();
  // SCENE.png beside SCENE.xml fills the Compare panel's field (and the panel says why).
  void fillReferenceBeside();
  void stopTradeoff(const std::string& why, bool restartRender);
  std::string whyNoTradeoff() const;
  FrameSaveContext frameSaveContext() const;

  // One UI frame (viewer_app_frame.cpp): input, the script, the panels, edits into restarts, the image.
  void drawFrame();
  ViewerLayout layout() const;
  Shortcuts handleInput(ViewerLayout& layout, std::vector<InputEvent> input,
                        std::optional<UnsavedPrompt::Answer>& keyAnswer);
  void applyImageView(const Shortcuts& shortcuts, const ViewerLayout& layout);
  void commitFrame(const ViewerLayout& layout);
  void drawImageArea(const ViewerLayout& layout);
  void finishFrame(const ViewerLayout& layout);
  double nextWaitSeconds(Clock::time_point now, bool rendererIdle) const;
  // Ctrl+O's field is taking the focus, or has keys typed before it to take: frames go on until it has them.
  bool typingAhead() const {
    return filePanel_.focusOpenPath || !filePanel_.typeAhead.empty() || filePanel_.enterAhead;
  }

  // The panels and what they ask for (viewer_app_panels.cpp).
  void drawPanels(const ViewerLayout& layout, PanelActions& actions);
  void drawPanelColumn(const ViewerLayout& layout, PanelActions& actions);
  // The overlays over the image area (viewer_app_overlays.cpp), placed by placeOverlays so that none covers another.
  void drawOverlays(const ViewerLayout& layout, const std::string& readout);
  std::vector<OverlayRect> keepClear(const ViewerLayout& layout) const;
  // What goes over every other overlay: why the process is being ended, the help; and, with RAYVIEW_PRINT_OVERLAYS,
  // where the recovery offer's buttons are.
  void drawOnTop(const ViewerLayout& layout, float margin);
  // RAYVIEW_PRINT_OVERLAYS: the progress bar's text, when it changes.
  void printProgress(const std::string& text);
  void apply(const PanelActions& actions, const Shortcuts& shortcuts);
  // Home, F11, E and Shift+E; the wheel's dolly toward the point under the cursor.
  void applyHabits(const Shortcuts& shortcuts);
  void dollyAtCursor(const Shortcuts& shortcuts, const ViewerLayout& layout);
  // Over the image: the picked mesh's outline; the lights and the orbit pivot while navigating (or always).
  void drawSceneMarks(const ViewerLayout& layout);
  // A click on the image: pick what it shows; a double-click also puts the orbit pivot there.
  void pickAt(double x, double y, bool doubleClick, const ViewerLayout& layout);
  void updateTitle();
  // Opening another scene or quitting from the window asks first when there are unsaved edits.
  void openFromUser(const std::string& path);
  void quitFromUser();
  void answerUnsaved(UnsavedPrompt::Answer answer);
  // SIGTERM, SIGHUP or SIGINT arrived (termination_notice.h): keep the edits, say so in the window and on stderr,
  // and end the process (exit 128 + signal).
  [[noreturn]] void endOnSignal(int signal);
  // Hands the termination watch what to say about the unsaved edits should a signal come now.
  void publishTerminationNote();

  ViewerOptions options_;
  Window window_;
  ImGuiLayer imgui_;
  NavigationInput navigation_;
  std::optional<ScriptRunner> script_;

  FilePanelState filePanel_;
  CameraPanelState cameraPanel_;
  DisplayOptions display_;

  LoadController load_;
  RenderController render_;
  CompareController compare_;
  TradeoffController tradeoff_;
  SaveController saves_;
  ImageViewController imageView_;
  UnsavedPrompt unsaved_;
  RecoveryController recovery_;

  std::string editProblem_;  // why the current edits are not rendered
  std::string endingMessage_;  // the process is being ended from outside: why, and where the edits are
  std::string terminationNote_;  // what the termination watch says about the edits (publishTerminationNote)
  Clock::time_point marksUntil_{};  // the lights and pivot stay drawn until then after a navigation
  bool printOverlays_ = false;  // RAYVIEW_PRINT_OVERLAYS: tools driving the window (tests) read the placement
  std::string printedOverlays_;
  std::string printedProgress_;
  std::string printedRecovery_;
  bool printedEnding_ = false;
  bool helpPrinted_ = false;  // the help's state last printed (`help shown`, `help hidden`)
  std::string shownTitle_;
  int framesToDraw_ = kSettleFrames;
  bool quit_ = false;
  int exitCode_ = 0;
};

}  // namespace rayview
