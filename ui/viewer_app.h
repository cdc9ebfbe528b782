#pragma once
// The viewer: one UI thread that sleeps until something happens, draws the newest complete pass and the
// panels, turns input into edits and edits into restarts. It never renders, never builds a BVH and never
// waits for either: the ProgressiveRenderer and the SceneLoaderTask do that on their own threads.

#include <chrono>
#include <exception>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "file_image_task.h"
#include "file_watch.h"
#include "image_texture.h"
#include "imgui_layer.h"
#include "navigation_input.h"
#include "image_placement.h"
#include "panels.h"
#include "rayview/progressive_renderer.h"
#include "recent_files.h"
#include "scene_loader_task.h"
#include "scene_session.h"
#include "script_runner.h"
#include "tradeoff_task.h"
#include "rayview/viewer.h"
#include "window.h"

namespace rayview {

// Frame pacing (seconds): how long the UI sleeps in each state when nothing arrives.
// A pass in flight wakes the loop itself (the renderer's frame listener posts an empty event); this is
// only the fallback, and the rate at which a running script's conditions are checked.
inline constexpr double kRenderingPollSeconds = 1.0 / 120.0;
inline constexpr double kRenderingFallbackSeconds = 0.25;
inline constexpr double kLoadingPollSeconds = 1.0 / 30.0;     // progress bar
inline constexpr double kMeasuringPollSeconds = 0.1;          // progress bar, drawn seldom: the cores measure
// Speed vs accuracy in the viewer: retries of a run slowed by other processes (the bench's default is 5).
inline constexpr int kViewerSlowedRetries = 1;
// A new result opens its panel and scrolls to it; ImGui applies the scroll in the frame after: the result is on
// screen (for scripts: measure-tradeoff is over) after this many frames.
inline constexpr int kRevealFrames = 2;
inline constexpr int kMinPlotWidth = 480;  // narrower, the plot's labels overlap
inline constexpr double kIdleWaitSeconds = 10.0;              // final image, nothing to watch
// Frames drawn after the last event so ImGui's hover and focus state settles.
inline constexpr int kSettleFrames = 2;
// The panel column's width at content scale 1, and at most this share of the window.
inline constexpr float kPanelWidth = 400.0f;
inline constexpr float kMaxPanelShare = 0.45f;
inline constexpr int kInitialWindowWidth = 1280;
inline constexpr int kInitialWindowHeight = 800;

class ViewerApp final : public ScriptHost {
 public:
  // Throws DisplayUnavailable when no window can be opened.
  ViewerApp(const ViewerOptions& options, std::optional<Script> script);
  ~ViewerApp() override;

  // Runs until the window closes, Ctrl+Q, or the script quits or fails. Returns the exit code.
  int run();

  // ScriptHost: what automation (and the keys and panels) can do.
  SceneSession* session() override { return session_.get(); }
  void open(const std::string& path) override;
  void reload() override;
  bool loading() const override { return awaitedLoad_ != 0; }
  std::string loadError() const override { return loadError_; }
  std::string scenePath() const override { return scenePath_; }
  std::uint64_t sceneSerial() const override { return sceneSerial_; }
  bool finalFrameShown() const override;
  std::string editProblem() const override { return editProblem_; }
  bool fileImageReady() override;
  std::filesystem::path saveFrame(const std::string& path, FrameSave what) override;
  void setImageView(bool imageView) override;
  std::filesystem::path saveScene(const std::string& path) override;
  void screenshot(const std::string& path) override { pendingScreenshot_ = path, captureOutcome_.reset(); }
  void saveView(const std::string& path) override { pendingViewSave_ = path, captureOutcome_.reset(); }
  std::optional<std::string> captureOutcome() const override { return captureOutcome_; }
  std::string stateLine() const override;
  void resizeWindow(int width, int height) override { window_.setSize(width, height); }
  void measureTradeoff(double resolutionScale) override;
  void cancelTradeoff() override { stopTradeoff("cancelled", true); }
  TradeoffState tradeoffState() const override;
  std::string loadReference(const std::string& path) override;
  std::optional<ImageError> finalComparison() const override;
  std::string comparisonProblem() const override;
  DisplayMapping displayMapping() const override { return display_.mapping; }
  void setDisplayMapping(const DisplayMapping& mapping) override { display_.mapping = mapping; }
  std::string applyTradeoff(const Knob* knob, int value) override;
  void quit(int exitCode) override;

 private:
  using Clock = std::chrono::steady_clock;
  struct Layout {
    float panelWidth = 0.0f;
    float viewX = 0.0f, viewY = 0.0f, viewWidth = 0.0f, viewHeight = 0.0f;      // the area for the image
    float imageX = 0.0f, imageY = 0.0f, imageWidth = 0.0f, imageHeight = 0.0f;  // the image as placed (placement_)
    float framebufferScale = 1.0f;
  };

  // Loading
  void requestLoad(const std::string& path, bool isReload);
  // The default render settings with the command line's knobs: what the first scene is loaded and rendered with.
  RenderSettings initialSettings() const;
  bool pollLoader();
  void adoptScene(LoadOutcome& outcome);
  bool pollFileWatch(Clock::time_point now);

  // Rendering
  void restartRender(std::shared_ptr<const PixelSource> source);
  bool takeNewFrame();
  void commitEdits();

  // Speed vs accuracy (viewer_tradeoff.cpp): the measurement pauses the render and any edit or load cancels it.
  bool measuring() const { return requestedTradeoff_.has_value() || awaitedTradeoff_ != 0; }
  std::string whyNoTradeoff() const;
  void startRequestedTradeoff(const Layout& layout);
  bool pollTradeoff();
  void stopTradeoff(const std::string& why, bool restartRender);
  // Apply: the setting of row `index` of the result shown goes into the session, as a Render panel edit.
  void applyTradeoffRow(std::size_t index);

  // The newest pass as displayed (exposure and gamma), uploaded if it or the mapping changed.
  const ImageTexture& renderTexture();
  // Comparing with a reference image (viewer_compare.cpp): the image the image area shows this frame (the
  // render, the reference while Space is held, or the difference), uploaded if it changed.
  const ImageTexture& shownImage();
  std::string viewLabel() const;  // what the image area shows, unless it is the render
  void toggleDifference();

  // The image view (viewer_image_view.cpp): fit, 1:1, zoom and pan from the keys and the mouse; the image
  // drawn where placement_ puts it, clipped to the image area, with a pixel grid at high zoom; the readout of
  // the pixel under the cursor.
  void applyImageView(const Shortcuts& shortcuts, const Layout& layout);
  // The window view's resolution for this layout (the image area in framebuffer pixels), or nullopt in the image
  // view; handed to the session before each commit.
  std::optional<std::pair<int, int>> windowViewSize(const Layout& layout) const;
  // The image shown is the one the session renders (not a pass of another view or size still on screen).
  bool frameIsRendered() const;
  // The file's image for saving in the window view (file_image_task.h): its result, once per request.
  bool pollFileImage();
  const Image& fileImage() const;
  void drawImage(const ImageTexture& shown, const Layout& layout);
  void drawPixelReadout(const Layout& layout);

  // One UI frame
  void drawFrame();
  Layout layout() const;
  void drawPanels(const Layout& layout, PanelActions& actions);
  void apply(const PanelActions& actions, const Shortcuts& shortcuts);
  void afterSwap();
  double nextWaitSeconds(Clock::time_point now, bool rendererIdle) const;

  // Unsaved edits: opening another scene or quitting from the window asks first (a modal: Save, Discard,
  // Cancel). Scripts' open and quit do not ask: they discard.
  enum class Confirm { None, Quit, Open };
  enum class Answer { Save, Discard, Cancel };
  void openFromUser(const std::string& path);
  void quitFromUser();
  void askBefore(Confirm what, const std::string& path);
  void drawUnsavedModal(std::optional<Answer> keyAnswer);
  void answerUnsaved(Answer answer);
  void updateTitle();
  // A click on the image: pick what it shows; a double-click also puts the orbit pivot there.
  void pickAt(double x, double y, bool doubleClick, const Layout& layout);

  // Saving with a message for the user (panel and stdout) instead of an exception.
  void saveFrameReporting();
  void saveSceneReporting(const std::string& path);
  void reportSaveFailure(const std::exception& error);

  ViewerOptions options_;
  bool knobsApplied_ = false;  // the command line's knobs went into the first scene loaded
  Window window_;
  ImGuiLayer imgui_;
  ImageTexture texture_;  // the render as displayed
  MappedImage shownRender_;
  ProgressiveRenderer renderer_;
  SceneLoaderTask loader_;
  RecentFiles recent_;
  FileWatch watch_;
  NavigationInput navigation_;
  std::optional<ScriptRunner> script_;
  TradeoffTask tradeoff_;
  ImageTexture plotTexture_;

  // The scene on screen.
  std::unique_ptr<SceneSession> session_;
  std::string scenePath_;
  std::string requestedPath_;  // of the newest open or reload (what F5 loads), even if it failed
  std::vector<Diagnostic> warnings_;
  std::uint64_t sceneSerial_ = 0;

  // The load in progress.
  std::uint64_t awaitedLoad_ = 0;
  bool awaitedIsReload_ = false;
  std::optional<AccelKind> rebuildRequested_;
  std::string loadError_;

  // The render.
  std::uint64_t generation_ = 0;  // of the latest restart
  ProgressiveFrame frame_;        // the newest pass of generation_ (or the last one before it): what is shown
  ProgressiveFrame incoming_;     // scratch for takeFrameIfNewer
  std::uint64_t seenVersion_ = 0;
  bool haveFrame_ = false;
  std::uint64_t shownVersion_ = 0;
  std::uint64_t announcedFinal_ = 0;
  bool interactive_ = false;
  std::string editProblem_;
  ViewerStats stats_;

  FilePanelState filePanel_;
  CameraPanelState cameraPanel_;
  DisplayOptions display_;
  // The measurement.
  TradeoffPanelState tradeoffPanel_;
  std::optional<double> requestedTradeoff_;  // started once this frame's edits are committed
  std::uint64_t awaitedTradeoff_ = 0;        // the running measurement's id
  std::uint64_t plotVersion_ = 0;
  std::uint64_t measuredSerial_ = 0, measuredCommit_ = 0;  // what the last measurement saw
  std::string tradeoffError_;                // why the newest measurement has no report
  int revealFrames_ = 0;                     // frames until a new result is on screen

  // Comparing with a reference image.
  ReferenceComparison comparison_;
  ComparePanelState comparePanel_;
  std::string pendingReference_;  // --compare: loaded once the first scene has loaded (or failed to)
  ImageTexture referenceTexture_;  // as displayed, like the render, so that Space flips between like and like
  MappedImage shownReference_;
  ImageTexture differenceTexture_;
  ImageView shownView_ = ImageView::Render;

  // The file's image rendered for saving while the window view is on: which edits it (or the running
  // request) is of, so that it is made once per state and never saved for other edits.
  struct FileImageKey {
    std::uint64_t scene = 0, commit = 0;
    const void* geometry = nullptr;
    bool operator==(const FileImageKey&) const = default;
  };
  FileImageKey fileImageKey() const;
  FileImageTask fileImageTask_;
  std::uint64_t awaitedFileImage_ = 0;
  FileImageKey awaitedFileImageKey_, fileImageOf_;
  std::optional<Image> fileImage_;

  // The image view.
  ImagePlacement placement_;
  int placedWidth_ = 0, placedHeight_ = 0;  // the image size the placement was made for
  std::optional<ImagePixel> readoutPixel_;  // the pixel under the cursor last frame, and what was shown of it
  std::string readoutText_;
  bool printReadout_ = false;               // RAYVIEW_PRINT_READOUT: tools driving the window read it on stdout

  Confirm confirm_ = Confirm::None;
  std::string confirmOpenPath_;
  std::string shownTitle_;

  std::string pendingScreenshot_;
  std::optional<std::string> captureOutcome_;  // the newest screenshot or view save: "" written, else why not
  std::optional<std::string> pendingViewSave_;  // "Save view as seen" ("": a numbered file), after this frame
  // Writes the image area of the frame just drawn (before the swap) as pendingViewSave_ says.
  void writeViewSave(int framebufferWidth, int framebufferHeight, const Layout& layout);
  int framesToDraw_ = kSettleFrames;
  bool quit_ = false;
  int exitCode_ = 0;
};

}  // namespace rayview
