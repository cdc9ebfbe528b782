// The viewer's UI loop: wait for events, pick up what the background threads produced, draw one frame; and the
// operations keys, panels and scripts share, each handed to its controller.
#include "viewer_app.h"

#include <algorithm>
#include <cstdio>
#include <unistd.h>

#include <csignal>
#include <cstdlib>
#include <utility>

#include <GLFW/glfw3.h>

#include "termination_notice.h"
#include "view_habits.h"

namespace rayview {

ViewerApp::ViewerApp(const ViewerOptions& options, std::optional<Script> script)
    : options_(options),
      window_("rayview", kInitialWindowWidth, kInitialWindowHeight),
      imgui_(window_.handle(), window_.contentScale(), window_.framebufferScale()),
      load_(options),
      render_(options.threads, options.farm),
      compare_(options.comparePath),
      tradeoff_(options.threads),
      saves_(options.threads, filePanel_),
      printOverlays_(std::getenv("RAYVIEW_PRINT_OVERLAYS") != nullptr) {
  if (script) script_.emplace(std::move(*script));
}

int ViewerApp::run() {
  load_.request(options_.scenePath, false);
  watchForTermination([] { glfwPostEmptyEvent(); }, options_.farm != nullptr);
  double waitSeconds = 0.0;
  while (!quit_) {
    window_.waitEvents(waitSeconds);
    if (const int signal = terminationSignal()) endOnSignal(signal);
    if (window_.shouldClose()) {
      if (!session() || !session()->unsaved()) break;
      window_.cancelClose();
      unsaved_.ask(UnsavedPrompt::Action::Quit, {});
      framesToDraw_ = kSettleFrames;
    }
    bool changed = window_.takeActivity();
    if (window_.takeContentScaleChange()) imgui_.setScale(window_.contentScale(), window_.framebufferScale());
    if (const std::vector<std::string> dropped = window_.takeDroppedPaths(); !dropped.empty()) openFromUser(dropped.front());
    changed |= pollTasks(Clock::now());
    recovery_.keep(session(), scenePath(), Clock::now());
    publishTerminationNote();
    // Read before taking the frame: when the renderer was idle, its last pass is certainly taken below.
    const bool rendererIdle = render_.idle();
    changed |= takeNewFrame();

    const bool scriptActive = script_ && script_->running();
    // A long full-resolution pass: its bar is redrawn at the fallback wake-up's pace (4 per second).
    const bool progressShown = render_.fullPassProgress(Clock::now()).has_value();
    if (changed || framesToDraw_ > 0 || scriptActive || typingAhead() || progressShown || loading() || tradeoff_.measuring() ||
        saves_.renderingFileImage() || saves_.captureRequested()) {
      drawFrame();
      framesToDraw_ = changed ? kSettleFrames : std::max(0, framesToDraw_ - 1);
    }
    if (script_ && script_->failed()) {
      std::fprintf(stderr, "rayview: script failed: %s\n", script_->failure().c_str());
      return 1;
    }
    waitSeconds = nextWaitSeconds(Clock::now(), rendererIdle);
  }
  // Quitting as asked: whatever is still unsaved was discarded (the question's Discard, a script's quit).
  if (exitCode_ == 0) recovery_.discard(scenePath());
  return exitCode_;
}

void ViewerApp::publishTerminationNote() {
  std::string note = recovery_.note(session(), scenePath());
  if (note == terminationNote_) return;
  terminationNote_ = note;
  setTerminationNote(std::move(note));
}

void ViewerApp::endOnSignal(int signal) {
  // The watch thread has said why and where the edits were at once; what was edited since is written now and said
  // again only when it changed the answer.
  const std::string kept = recovery_.keepNow(session(), scenePath());
  if (kept != terminationNote_) std::fprintf(stderr, "rayview: %s.\n", kept.c_str());
  endingMessage_ = terminationReason(signal) + ".\n" + kept + ".";
  // Shown until shortly before the watch ends the process (or mpirun's SIGKILL comes), so the window says it.
  const auto until = Clock::now() + kTerminationGrace - std::chrono::milliseconds(200);
  while (Clock::now() < until) {
    drawFrame();
    window_.waitEvents(0.05);
  }
  // As the signal's default action would, and at once: under mpirun, waiting for the other ranks' goodbyes would
  // only meet mpirun's SIGKILL.
  std::fflush(stdout);
  std::fflush(stderr);
  ::_exit(128 + signal);
}

bool ViewerApp::pollTasks(Clock::time_point now) {
  const LoadEvent event = load_.poll(windowViewSize(layout(), display_.imageView));
  onLoad(event);
  bool changed = event.kind != LoadEvent::Kind::None;
  // --compare is checked against the size of the first scene's image.
  if (!loading())
    if (std::optional<std::string> pending = compare_.takePending()) loadReference(*pending);
  if (load_.reloadIfChanged(now, filePanel_.reloadOnChange)) {
    stopTradeoff("cancelled: a scene is loading", true);
    changed = true;
  }
  if (tradeoff_.poll(session(), sceneSerial())) {
    if (session()) render_.restart(session()->currentSource());
    changed = true;
  }
  changed |= saves_.pollFileImage();
  return changed;
}

bool ViewerApp::takeNewFrame() {
  if (!render_.takeNewFrame()) return false;
  ViewerStats& stats = render_.stats();
  stats.windowView = !display_.imageView;
  if (session()) {
    stats.fileWidth = session()->committedEdits().camera.width;
    stats.fileHeight = session()->committedEdits().camera.height;
  }
  // The figures against a reference follow each final pass, never a coarse one.
  compare_.compareFinal(render_.frame());
  return true;
}

void ViewerApp::onLoad(const LoadEvent& event) {
  if (event.kind == LoadEvent::Kind::None || event.kind == LoadEvent::Kind::Failed) return;
  SceneSession& s = *session();
  ViewerStats& stats = render_.stats();
  stats.bvhBuildMs = event.buildMs;
  stats.accel = s.geometry().accel->kind();
  stats.traversal = traversalBuilt(s.settings().accel, stats.accel, s.loaded().triangles.size());
  if (event.kind == LoadEvent::Kind::Rebuilt) return render_.restart(s.currentSource());
  navigation_.cancel();
  saves_.sceneReplaced(event.anotherScene);
  if (event.anotherScene) recovery_.sceneOpened(scenePath());
  editProblem_.clear();
  stats.triangles = s.loaded().triangles.size();
  stats.readMs = event.readMs;
  filePanel_.openPath = scenePath();
  if (filePanel_.saveScenePath.empty() || event.anotherScene) filePanel_.saveScenePath = suggestedSaveAsPath(scenePath());
  if (event.anotherScene) fillReferenceBeside();
  // A kept camera is committed before the first restart, so the file's view never flashes up.
  std::shared_ptr<const PixelSource> source = s.commit(editProblem_);
  render_.restart(source ? std::move(source) : s.currentSource());
}

void ViewerApp::fillReferenceBeside() {
  ComparePanelState& panel = compare_.panel();
  // Never over a reference the user gave (--compare, or one typed or loaded).
  if (compare_.comparison().loaded() || (!panel.path.empty() && !panel.filledBeside) || !options_.comparePath.empty())
    return;
  const std::optional<std::string> beside = referenceBeside(scenePath());
  panel.path = beside.value_or(std::string());
  panel.filledBeside = beside.has_value();
  if (!beside) return;
  panel.reveal = true;
  std::printf("reference beside the scene %s\n", beside->c_str());
  std::fflush(stdout);
}

void ViewerApp::commitEdits() {
  if (!session()) return;
  if (std::shared_ptr<const PixelSource> source = session()->commit(editProblem_)) {
    stopTradeoff("cancelled: the scene was edited", false);
    render_.restart(std::move(source));
  }
  // Another traversal back-end was chosen: prepare the geometry again in the background.
  if (load_.rebuildWanted()) {
    stopTradeoff("cancelled: the traversal changed", true);
    load_.requestRebuild();
  }
}

void ViewerApp::stopTradeoff(const std::string& why, bool restartRender) {
  if (tradeoff_.stop(why) && restartRender && session()) render_.restart(session()->currentSource());
}

std::string ViewerApp::whyNoTradeoff() const {
  if (!load_.session()) return "no scene yet";
  if (loading()) return "a scene is loading";
  if (!editProblem_.empty()) return "the edits cannot be rendered";
  return {};
}

bool ViewerApp::finalFrameShown() const {
  const SceneSession* s = load_.session();
  return s && render_.finalPassShown() && !s->hasPendingEdits() && !s->needsRebuild() && editProblem_.empty();
}

FrameSaveContext ViewerApp::frameSaveContext() const {
  FrameSaveContext c;
  c.session = load_.session();
  c.sceneSerial = sceneSerial();
  c.finalShown = finalFrameShown();
  c.imageView = display_.imageView;
  c.shown = render_.haveFrame() ? &render_.frame().image : nullptr;
  c.scenePath = scenePath();
  c.mapping = display_.mapping;
  return c;
}

void ViewerApp::open(const std::string& path) {
  stopTradeoff("cancelled: a scene is loading", true);
  // Asked (the question answered, or a script): the edits on screen are given up. Kept again if the load fails.
  recovery_.discard(scenePath());
  load_.open(path);
}

void ViewerApp::reload() {
  stopTradeoff("cancelled: a scene is loading", true);
  load_.reload();
}

void ViewerApp::setModelUp(ModelUpAxis up) {
  if (isModelFile(scenePath()) && up != load_.modelUp()) stopTradeoff("cancelled: a scene is loading", true);
  load_.setModelUp(up);
}

std::string ViewerApp::answerRecovery(bool restore) {
  framesToDraw_ = kSettleFrames;
  return recovery_.answer(restore, session());
}

void ViewerApp::quit(int exitCode) {
  exitCode_ = exitCode;
  quit_ = true;
}

std::filesystem::path ViewerApp::saveFrame(const std::string& path, FrameSave what) {
  return saves_.saveFrame(frameSaveContext(), path, what);
}

std::filesystem::path ViewerApp::saveScene(const std::string& path) {
  return saves_.saveScene(session(), scenePath(), path);
}

void ViewerApp::setImageView(bool imageView) {
  if (display_.imageView == imageView) return;
  display_.imageView = imageView;
  framesToDraw_ = kSettleFrames;
  // The next commit restarts the render at the view's resolution; saves and compares follow the file's image.
  std::printf("view %s\n", imageView ? "image" : "window");
  std::fflush(stdout);
}

std::string ViewerApp::loadReference(const std::string& path) {
  framesToDraw_ = kSettleFrames;
  // The reference must be the size of the image the scene renders (the camera's resolution, edits included).
  const Camera* camera = session() ? &session()->committedEdits().camera : nullptr;
  if (std::string error = compare_.load(path, camera ? camera->width : 0, camera ? camera->height : 0); !error.empty())
    return error;
  // A reference is of the file's image: compare, flip and difference in the image view, pixel for pixel.
  setImageView(true);
  // A final pass already on screen is compared at once; otherwise the next final pass is.
  if (render_.haveFrame()) compare_.compareFinal(render_.frame());
  return {};
}

std::optional<ImageError> ViewerApp::finalComparison() const {
  if (!finalFrameShown()) return std::nullopt;
  std::optional<ImageError> figures = compare_.figuresOf(render_.frame().version);
  // A reference is of the file's camera: the figures say when the one on screen is not that any more.
  const SceneSession* shown = load_.session();
  if (figures && shown && !(shown->committedEdits().camera == shown->loaded().camera))
    figures->cameraMismatch = "the viewer's camera is not the scene file's";
  return figures;
}

std::string ViewerApp::comparisonProblem() const {
  std::optional<std::pair<int, int>> finalSize;
  if (finalFrameShown()) finalSize = std::pair{render_.frame().width, render_.frame().height};
  return compare_.problem(display_.imageView, finalSize);
}

double ViewerApp::nextWaitSeconds(Clock::time_point now, bool rendererIdle) const {
  if (framesToDraw_ > 0 || saves_.captureRequested() || typingAhead()) return 0.0;
  double wait = kIdleWaitSeconds;
  if (const std::optional<double> look = load_.secondsUntilNextLook(now); look && filePanel_.reloadOnChange)
    wait = std::min(wait, *look + 0.001);
  if (loading()) wait = std::min(wait, kLoadingPollSeconds);
  if (tradeoff_.measuring()) wait = std::min(wait, kMeasuringPollSeconds);
  if (saves_.renderingFileImage()) wait = std::min(wait, kLoadingPollSeconds);  // its progress in the Save panel
  if (const std::optional<double> toast = saves_.secondsUntilToastEnds(now)) wait = std::min(wait, *toast + 0.001);
  if (const std::optional<double> due = recovery_.secondsUntilDue(now)) wait = std::min(wait, *due + 0.001);
  if (now < marksUntil_) wait = std::min(wait, std::chrono::duration<double>(marksUntil_ - now).count() + 0.001);
  // A script condition to check: look again soon. A pass in flight wakes us when it is published.
  if (script_ && script_->running()) wait = std::min(wait, kRenderingPollSeconds);
  if (!rendererIdle) wait = std::min(wait, kRenderingFallbackSeconds);
  return wait;
}

}  // namespace rayview
