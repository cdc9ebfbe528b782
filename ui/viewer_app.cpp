// The viewer's UI loop: wait for events, pick up what the background threads produced, draw one frame.
#include "viewer_app.h"

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <utility>

#include <GL/gl.h>
#include <GLFW/glfw3.h>
#include <imgui.h>

#include "rayview/process_memory.h"
#include "window_capture.h"

namespace rayview {
ViewerApp::ViewerApp(const ViewerOptions& options, std::optional<Script> script)
    : options_(options),
      window_("rayview", kInitialWindowWidth, kInitialWindowHeight),
      imgui_(window_.handle(), window_.contentScale(), window_.framebufferScale()),
      renderer_(options.threads),
      recent_(RecentFiles::defaultStorage()),
      tradeoff_(options.threads),
      pendingReference_(options.comparePath),
      fileImageTask_(options.threads),
      printReadout_(std::getenv("RAYVIEW_PRINT_READOUT") != nullptr) {
  if (script) script_.emplace(std::move(*script));
  stats_.threads = renderer_.threads();
  // Wake the UI loop when a pass is published, so it can sleep while passes render.
  renderer_.setFrameListener([] { glfwPostEmptyEvent(); });
  tradeoff_.setFinishedListener([] { glfwPostEmptyEvent(); });
  fileImageTask_.setFinishedListener([] { glfwPostEmptyEvent(); });
}

ViewerApp::~ViewerApp() {
  renderer_.restart(nullptr);  // stop the pass in flight now rather than let the renderer finish it on exit
}

int ViewerApp::run() {
  requestLoad(options_.scenePath, false);
  double waitSeconds = 0.0;
  while (!quit_) {
    window_.waitEvents(waitSeconds);
    if (window_.shouldClose()) {
      if (!session_ || !session_->unsaved()) break;
      window_.cancelClose();
      askBefore(Confirm::Quit, {});
    }
    const Clock::time_point now = Clock::now();

    bool changed = window_.takeActivity();
    if (window_.takeContentScaleChange()) imgui_.setScale(window_.contentScale(), window_.framebufferScale());
    if (const std::vector<std::string> dropped = window_.takeDroppedPaths(); !dropped.empty()) openFromUser(dropped.front());
    changed |= pollLoader();
    // --compare is checked against the size of the first scene's image.
    if (!pendingReference_.empty() && !loading()) loadReference(std::exchange(pendingReference_, {}));
    changed |= pollFileWatch(now);
    changed |= pollTradeoff();
    changed |= pollFileImage();
    // Read before taking the frame: when the renderer was idle, its last pass is certainly taken below.
    const bool rendererIdle = renderer_.idle();
    changed |= takeNewFrame();

    const bool scriptActive = script_ && script_->running();
    if (changed || framesToDraw_ > 0 || scriptActive || loading() || measuring() || awaitedFileImage_ != 0 ||
        !pendingScreenshot_.empty() || pendingViewSave_) {
      drawFrame();
      framesToDraw_ = changed ? kSettleFrames : std::max(0, framesToDraw_ - 1);
    }
    if (script_ && script_->failed()) {
      std::fprintf(stderr, "rayview: script failed: %s\n", script_->failure().c_str());
      return 1;
    }
    waitSeconds = nextWaitSeconds(Clock::now(), rendererIdle);
  }
  return exitCode_;
}

double ViewerApp::nextWaitSeconds(Clock::time_point now, bool rendererIdle) const {
  if (framesToDraw_ > 0 || !pendingScreenshot_.empty() || pendingViewSave_) return 0.0;
  double wait = kIdleWaitSeconds;
  if (watch_.active() && filePanel_.reloadOnChange) wait = std::min(wait, watch_.secondsUntilNextLook(now) + 0.001);
  if (loading()) wait = std::min(wait, kLoadingPollSeconds);
  if (measuring()) wait = std::min(wait, kMeasuringPollSeconds);
  if (awaitedFileImage_ != 0) wait = std::min(wait, kLoadingPollSeconds);  // its progress in the Save panel
  // A script condition to check: look again soon. A pass in flight wakes us when it is published.
  if (script_ && script_->running()) wait = std::min(wait, kRenderingPollSeconds);
  if (!rendererIdle) wait = std::min(wait, kRenderingFallbackSeconds);
  return wait;
}

bool ViewerApp::takeNewFrame() {
  if (!renderer_.takeFrameIfNewer(seenVersion_, incoming_)) return false;
  seenVersion_ = incoming_.version;
  // A pass that was published just before the latest restart belongs to the old edits: never show it.
  if (incoming_.generation < generation_) return false;
  std::swap(frame_, incoming_);
  haveFrame_ = true;
  stats_.generation = frame_.generation;
  stats_.editToFirstPassMs = frame_.firstPassMsSinceRestart;
  stats_.editToFinalPassMs = frame_.final ? frame_.msSinceRestart : -1.0;
  stats_.stride = frame_.stride;
  stats_.samples = frame_.samples;
  stats_.final = frame_.final;
  stats_.passMs = frame_.passMs;
  stats_.megaRaysPerSecond = frame_.megaRaysPerSecond;
  // Read with each pass shown: at most once a frame drawn, never while idle (rayview/process_memory.h: ~20 us).
  const ProcessMemory memory = processMemory();
  stats_.residentBytes = memory.resident;
  stats_.peakResidentBytes = memory.peak;
  stats_.width = frame_.width;
  stats_.height = frame_.height;
  stats_.windowView = !display_.imageView;
  if (session_) {
    stats_.fileWidth = session_->committedEdits().camera.width;
    stats_.fileHeight = session_->committedEdits().camera.height;
  }
  // The figures against a reference follow each final pass, never a coarse one.
  if (frame_.final) comparison_.compareFinal(frame_.image, frame_.version);
  return true;
}

void ViewerApp::restartRender(std::shared_ptr<const PixelSource> source) {
  generation_ = renderer_.restart(std::move(source));
}

void ViewerApp::commitEdits() {
  if (!session_) return;
  if (std::shared_ptr<const PixelSource> source = session_->commit(editProblem_)) {
    stopTradeoff("cancelled: the scene was edited", false);
    restartRender(std::move(source));
  }
  // Another traversal back-end was chosen: prepare the geometry again in the background.
  if (session_->needsRebuild() && !loading() && rebuildRequested_ != session_->settings().accel) {
    stopTradeoff("cancelled: the traversal changed", true);
    rebuildRequested_ = session_->settings().accel;
    LoadRequest request;
    request.path = scenePath_;
    request.accel = session_->settings().accel;
    request.rebuildOf = session_->loadedShared();
    awaitedLoad_ = loader_.request(std::move(request));
    awaitedIsReload_ = false;
  }
}

ViewerApp::Layout ViewerApp::layout() const {
  const ImGuiIO& io = ImGui::GetIO();
  Layout l;
  l.panelWidth = display_.hidePanels ? 0.0f : std::min(kPanelWidth * imgui_.layoutScale(), io.DisplaySize.x * kMaxPanelShare);
  l.viewX = l.panelWidth;
  l.viewWidth = std::max(io.DisplaySize.x - l.panelWidth, 1.0f);
  l.viewHeight = std::max(io.DisplaySize.y, 1.0f);
  l.framebufferScale = window_.framebufferScale();
  if (!display_.imageView) {
    // The window view: the render is the image area's own pixels.
    l.imageX = l.viewX;
    l.imageY = l.viewY;
    l.imageWidth = l.viewWidth;
    l.imageHeight = l.viewHeight;
  } else if (session_) {
    // The image view: the file's image, fitted (aspect kept, square pixels) unless the user zoomed
    // (image_placement.h). The image's size, not the texture's: a coarse pass's texture holds one texel per block.
    const Camera& file = session_->committedEdits().camera;
    const ScreenRect placed =
        placement_.place({l.viewX, l.viewY, l.viewWidth, l.viewHeight}, file.width, file.height, l.framebufferScale);
    l.imageX = static_cast<float>(placed.x);
    l.imageY = static_cast<float>(placed.y);
    l.imageWidth = static_cast<float>(placed.width);
    l.imageHeight = static_cast<float>(placed.height);
  }
  return l;
}

const ImageTexture& ViewerApp::renderTexture() {
  if (haveFrame_)
    texture_.update(shownRender_.of(frame_.image, frame_.version, display_.mapping), shownRender_.serial());
  return texture_;
}

void ViewerApp::drawFrame() {
  renderTexture();  // before the layout, which fits the texture's size
  imgui_.beginFrame();
  const ImGuiIO& io = ImGui::GetIO();
  Layout l = layout();

  Shortcuts shortcuts;
  std::vector<InputEvent> input = window_.takeInput();
  // While the unsaved-edits question is up, keys answer it and nothing reaches the view.
  std::optional<Answer> keyAnswer;
  if (confirm_ != Confirm::None) {
    for (const InputEvent& e : input) {
      if (e.kind != InputEvent::Kind::Key || !e.pressed || e.repeat || keyAnswer) continue;
      if (e.key == GLFW_KEY_S || e.key == GLFW_KEY_ENTER) keyAnswer = Answer::Save;
      else if (e.key == GLFW_KEY_D) keyAnswer = Answer::Discard;
      else if (e.key == GLFW_KEY_ESCAPE || e.key == GLFW_KEY_C) keyAnswer = Answer::Cancel;
    }
    input.clear();
    navigation_.releaseKeys();  // a release of a held key would not reach it
  }
  // While Ctrl+O's focus is on its way to the path field, typed keys belong to the field, not to shortcuts.
  // Orbit and pan speeds follow the image as shown, up to the view's size (a zoomed-in image turns no slower).
  const float navigationHeight = l.imageHeight > 0.0f ? std::min(l.imageHeight, l.viewHeight) : l.viewHeight;
  navigation_.handle(input, io.WantCaptureMouse, io.WantCaptureKeyboard || filePanel_.focusOpenPath,
                     l.viewHeight, navigationHeight, session_.get(), shortcuts);
  applyImageView(shortcuts, l);
  l = layout();
  if (shortcuts.focusOpen) {
    // Before the panels are drawn, so the Scene panel already holds this frame's typed characters.
    filePanel_.focusOpenPath = true;
    filePanel_.focusFrames = 0;
    filePanel_.typeAhead.clear();
  }
  if (script_ && script_->running()) script_->step(*this);

  PanelActions actions;
  drawPanels(l, actions);
  drawUnsavedModal(keyAnswer);
  apply(actions, shortcuts);
  if (shortcuts.click) pickAt(shortcuts.click->first, shortcuts.click->second, shortcuts.doubleClick, l);

  // Hold the coarse level while the user drags the view or a value.
  const bool dragging = navigation_.dragging() || (ImGui::IsAnyItemActive() && io.MouseDown[0]);
  if (dragging != interactive_) {
    interactive_ = dragging;
    renderer_.setInteractive(dragging);
  }
  // One drag, or one value held or typed in a panel, is one undo step.
  if (session_) session_->setGesture(navigation_.dragging() || ImGui::IsAnyItemActive());
  if (session_) session_->setViewport(windowViewSize(l));
  commitEdits();
  updateTitle();
  startRequestedTradeoff(l);

  if (const ImageTexture& shown = shownImage(); !shown.empty()) drawImage(shown, l);
  if (!pendingViewSave_) {
    drawPixelReadout(l);
    drawViewLabel(viewLabel(), l.viewX + l.viewWidth - ImGui::GetStyle().WindowPadding.x,
                  l.viewY + ImGui::GetStyle().WindowPadding.y);
  }

  int framebufferWidth = 0, framebufferHeight = 0;
  window_.framebufferSize(framebufferWidth, framebufferHeight);
  glViewport(0, 0, framebufferWidth, framebufferHeight);
  glClearColor(0.09f, 0.09f, 0.1f, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT);
  imgui_.render();
  if (pendingViewSave_) writeViewSave(framebufferWidth, framebufferHeight, l);
  if (!pendingScreenshot_.empty()) {
    const std::string path = std::exchange(pendingScreenshot_, {});
    try {
      writeImageFile(path, readWindowPixels(framebufferWidth, framebufferHeight));
      captureOutcome_ = std::string();
      std::printf("screenshot %s\n", path.c_str());
      std::fflush(stdout);
    } catch (const ImageIoError& error) {
      captureOutcome_ = error.what();
      filePanel_.lastSaved = std::string("screenshot failed: ") + error.what();
      filePanel_.lastSaveFailed = true;
      std::fprintf(stderr, "rayview: %s\n", error.what());
    }
  }
  window_.swapBuffers();
  if (revealFrames_ > 0) --revealFrames_;
  afterSwap();
}

void ViewerApp::afterSwap() {
  if (!haveFrame_) return;
  shownVersion_ = frame_.version;
  if (finalFrameShown() && announcedFinal_ != frame_.generation) {
    announcedFinal_ = frame_.generation;
    // Tests and tools driving the window wait for this line.
    std::printf("final pass generation %llu\n", static_cast<unsigned long long>(frame_.generation));
    std::fflush(stdout);
  }
  // Ctrl+S pressed while refining saves once the file's image is ready (the final pass on screen in the image
  // view; rendered in the background after it in the window view).
  if (filePanel_.frameSavePending && fileImageReady()) saveFrameReporting();
}

bool ViewerApp::finalFrameShown() const {
  return session_ && haveFrame_ && frame_.final && frame_.generation == generation_ && shownVersion_ == frame_.version &&
         !session_->hasPendingEdits() && !session_->needsRebuild() && editProblem_.empty();
}

void ViewerApp::drawPanels(const Layout& l, PanelActions& actions) {
  const ImGuiWindowFlags flags = ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse |
                                 ImGuiWindowFlags_NoTitleBar | ImGuiWindowFlags_NoBringToFrontOnFocus;
  if (display_.hidePanels) {
    // The image has the whole window; one small button brings the column back.
    ImGui::SetNextWindowPos(ImVec2(0.0f, 0.0f));
    if (ImGui::Begin("##showpanels", nullptr, flags | ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoSavedSettings))
      if (ImGui::Button("Show panels (F9)")) actions.togglePanels = true;
    ImGui::End();
  }
  if (!display_.hidePanels) {
    ImGui::SetNextWindowPos(ImVec2(0.0f, 0.0f));
    ImGui::SetNextWindowSize(ImVec2(l.panelWidth, l.viewHeight));
  }
  if (!display_.hidePanels && ImGui::Begin("rayview", nullptr, flags)) {
    if (ImGui::SmallButton("Hide panels (F9)")) actions.togglePanels = true;
    ImGui::PushItemWidth(-ImGui::GetFontSize() * 9.0f);  // room for the labels on the right
    const SceneInfo info{scenePath_.empty() ? (session_ ? "default scene (embedded)" : "no scene yet") : scenePath_,
                         warnings_};
    drawScenePanel(filePanel_, recent_, info, loader_.progress(), actions);
    if (filePanel_.frameSavePending && awaitedFileImage_ != 0 && session_) {
      const Camera& file = session_->committedEdits().camera;
      filePanel_.lastSaved = "rendering the file's " + std::to_string(file.width) + "x" + std::to_string(file.height) +
                             " image to save: " +
                             std::to_string(static_cast<int>(100.0 * fileImageTask_.progress())) + "%";
    }
    drawSavePanel(filePanel_, haveFrame_, actions);
    if (session_) {
      drawCameraPanel(*session_, cameraPanel_, editProblem_, actions);
      drawRenderSettingsPanel(*session_, display_);
      drawLightsPanel(session_->edits(), session_->bounds().radius());
      const std::optional<std::size_t> picked =
          session_->selection() ? std::optional<std::size_t>(session_->selection()->material) : std::nullopt;
      drawMaterialsPanel(session_->edits(), session_->loaded().texture.has_value(), picked,
                         session_->takeMaterialReveal());
      const std::string why = whyNoTradeoff();
      drawTradeoffPanel(tradeoffPanel_, session_->edits(), session_->settings(), why.empty(), why, actions);
    }
    const CompareInfo compare{comparison_, haveFrame_ ? frame_.width : 0, haveFrame_ ? frame_.height : 0,
                              finalComparison().has_value()};
    drawComparePanel(comparePanel_, compare, actions);
    ImGui::PopItemWidth();
  }
  if (!display_.hidePanels) ImGui::End();

  const float margin = ImGui::GetStyle().WindowPadding.x;
  // In a small window the stats take one line, so they do not cover the image.
  const ImGuiIO& io = ImGui::GetIO();
  const float scale = imgui_.layoutScale();
  const bool smallWindow = io.DisplaySize.x < kCompactStatsWidth * scale || io.DisplaySize.y < kCompactStatsHeight * scale;
  // Saving the view as seen: the image area alone, no overlay over it.
  if (pendingViewSave_) return;
  if (display_.showStats && haveFrame_)
    drawStatsOverlay(stats_, l.viewX + l.viewWidth - margin, l.viewY + l.viewHeight - margin,
                     display_.oneLineStats || smallWindow);
  const std::string stillShowing =
      session_ ? (scenePath_.empty() ? std::string("the default scene") : scenePath_) : std::string();
  const float belowError =
      drawErrorOverlay(loadError_, stillShowing, l.viewX + margin, l.viewY + margin, l.viewWidth - 2.0f * margin);
  const float belowLoading = drawLoadingOverlay(loader_.progress(), l.viewX + margin, belowError,
                                                std::min(l.viewWidth - 2.0f * margin, 480.0f * imgui_.layoutScale()));
  drawTradeoffPlot(tradeoffPanel_, plotTexture_, l.viewX + margin, belowLoading, l.viewWidth - 2.0f * margin,
                   l.viewY + l.viewHeight - margin - belowLoading);
}

void ViewerApp::apply(const PanelActions& actions, const Shortcuts& shortcuts) {
  if (actions.open) openFromUser(*actions.open);
  if (actions.reload || shortcuts.reload) reload();
  if (actions.saveFrame || shortcuts.saveFrame) saveFrameReporting();
  if (actions.saveView) pendingViewSave_ = std::string();  // drawn and read back next frame
  if (actions.saveSceneNumbered || shortcuts.saveScene) saveSceneReporting({});
  if (actions.saveSceneAs) saveSceneReporting(*actions.saveSceneAs);
  if (actions.cancelTradeoff) cancelTradeoff();
  if (actions.measureTradeoff) measureTradeoff(*actions.measureTradeoff);
  if (actions.loadReference) loadReference(*actions.loadReference);
  if (actions.toggleDifference || shortcuts.toggleDifference) toggleDifference();
  if (actions.applyTradeoffRow) applyTradeoffRow(*actions.applyTradeoffRow);
  if (shortcuts.quit) quitFromUser();
  if (session_ && shortcuts.undo) session_->undo();
  if (session_ && shortcuts.redo) session_->redo();
  if (actions.togglePanels || shortcuts.togglePanels) {
    display_.hidePanels = !display_.hidePanels;
    std::printf("panels %s\n", display_.hidePanels ? "hidden" : "shown");
    std::fflush(stdout);
  }
  if (session_ && (actions.frameScene || shortcuts.frameScene))
    session_->navigate([&](OrbitCamera& o) { o.frame(session_->framingBounds()); });
  if (session_ && (actions.resetCamera || shortcuts.resetCamera)) session_->navigate([](OrbitCamera& o) { o.reset(); });
}

void ViewerApp::pickAt(double x, double y, bool doubleClick, const Layout& l) {
  if (!session_) return;
  // Only on the image area, and there on the image as placed (fitted or zoomed).
  if (x < l.viewX || x >= l.viewX + l.viewWidth || y < l.viewY || y >= l.viewY + l.viewHeight) return;
  // A pixel of the image the session renders (the window view's or the file's): the ray through it.
  const Camera camera = session_->renderedCamera();
  const std::optional<ImagePixel> pixel =
      ImagePlacement::pixelAt({l.imageX, l.imageY, l.imageWidth, l.imageHeight}, camera.width, camera.height,
                              screenPixelCentre(x, l.framebufferScale), screenPixelCentre(y, l.framebufferScale));
  if (!pixel) return;
  const std::optional<PickResult> pick = session_->pickRendered(pixel->i, pixel->j);
  std::printf("%s\n", pick ? describePick(*pick, session_->loaded(), session_->edits()).c_str() : "picked nothing");
  std::fflush(stdout);
  if (pick && doubleClick) session_->navigate([&](OrbitCamera& o) { o.setPivot(pick->point); });
}

void ViewerApp::updateTitle() {
  std::string title = "rayview - " + (scenePath_.empty() ? std::string("default scene") : scenePath_);
  if (session_ && session_->unsaved()) title += " *";
  if (title != shownTitle_) window_.setTitle(shownTitle_ = title);
}

void ViewerApp::openFromUser(const std::string& path) {
  if (session_ && session_->unsaved()) return askBefore(Confirm::Open, path);
  open(path);
}

void ViewerApp::quitFromUser() {
  if (session_ && session_->unsaved()) return askBefore(Confirm::Quit, {});
  quit(0);
}

void ViewerApp::askBefore(Confirm what, const std::string& path) {
  if (confirm_ == Confirm::None) {
    std::printf("unsaved edits: save, discard or cancel?\n");
    std::fflush(stdout);
  }
  confirm_ = what;
  confirmOpenPath_ = path;
  framesToDraw_ = kSettleFrames;
}

void ViewerApp::drawUnsavedModal(std::optional<Answer> keyAnswer) {
  if (confirm_ == Confirm::None) return;
  constexpr const char* kTitle = "Unsaved edits";
  if (!ImGui::IsPopupOpen(kTitle)) ImGui::OpenPopup(kTitle);
  const ImGuiIO& io = ImGui::GetIO();
  ImGui::SetNextWindowPos(ImVec2(io.DisplaySize.x * 0.5f, io.DisplaySize.y * 0.5f), ImGuiCond_Always, ImVec2(0.5f, 0.5f));
  std::optional<Answer> answer = keyAnswer;
  if (ImGui::BeginPopupModal(kTitle, nullptr, ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoMove)) {
    ImGui::TextUnformatted("The scene has edits that are not saved.");
    if (confirm_ == Confirm::Quit) ImGui::TextUnformatted("Save them (as a new numbered file) before quitting?");
    else ImGui::Text("Save them (as a new numbered file) before opening %s?", confirmOpenPath_.c_str());
    if (ImGui::Button("Save (S)")) answer = Answer::Save;
    ImGui::SameLine();
    if (ImGui::Button("Discard (D)")) answer = Answer::Discard;
    ImGui::SameLine();
    if (ImGui::Button("Cancel (Esc)")) answer = Answer::Cancel;
    if (answer) ImGui::CloseCurrentPopup();
    ImGui::EndPopup();
  }
  if (answer) answerUnsaved(*answer);
}

void ViewerApp::answerUnsaved(Answer answer) {
  const Confirm what = std::exchange(confirm_, Confirm::None);
  const char* names[] = {"save", "discard", "cancel"};
  std::printf("answered %s\n", names[static_cast<int>(answer)]);
  std::fflush(stdout);
  framesToDraw_ = kSettleFrames;
  if (answer == Answer::Cancel) return;
  if (answer == Answer::Save) {
    saveSceneReporting({});
    if (filePanel_.lastSaveFailed) return;  // the edits are still unsaved: stay
  }
  if (what == Confirm::Quit) quit(0);
  else open(confirmOpenPath_);
}

}  // namespace rayview
