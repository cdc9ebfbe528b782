// One UI frame of the viewer: input, the script's step, the panels, edits into restarts, the image area, the
// captures asked for, the swap.
#include <algorithm>

#include <GL/gl.h>
#include <GLFW/glfw3.h>
#include <imgui.h>

#include "viewer_app.h"

namespace rayview {

ViewerLayout ViewerApp::layout() const {
  const ImGuiIO& io = ImGui::GetIO();
  ViewerLayout l;
  l.panelWidth = display_.hidePanels ? 0.0f : std::min(kPanelWidth * imgui_.layoutScale(), io.DisplaySize.x * kMaxPanelShare);
  l.viewX = l.panelWidth;
  l.viewWidth = std::max(io.DisplaySize.x - l.panelWidth, 1.0f);
  l.viewHeight = std::max(io.DisplaySize.y, 1.0f);
  l.framebufferScale = window_.framebufferScale();
  const Camera* file = load_.session() ? &load_.session()->committedEdits().camera : nullptr;
  imageView_.place(l, display_.imageView, file ? file->width : 0, file ? file->height : 0);
  return l;
}

namespace {

// Keys pressed and released again within `input` (since the last frame), each once.
std::vector<int> quickPresses(const std::vector<InputEvent>& input) {
  std::vector<int> quick;
  for (std::size_t i = 0; i < input.size(); ++i) {
    const InputEvent& e = input[i];
    if (e.kind != InputEvent::Kind::Key || !e.pressed || std::find(quick.begin(), quick.end(), e.key) != quick.end())
      continue;
    bool releasedAfter = false;
    for (std::size_t j = i + 1; j < input.size(); ++j)
      if (input[j].kind == InputEvent::Kind::Key && input[j].key == e.key) releasedAfter = !input[j].pressed;
    if (releasedAfter) quick.push_back(e.key);
  }
  return quick;
}

}  // namespace

Shortcuts ViewerApp::handleInput(ViewerLayout& l, std::vector<InputEvent> input,
                                 std::optional<UnsavedPrompt::Answer>& keyAnswer) {
  const ImGuiIO& io = ImGui::GetIO();
  Shortcuts shortcuts;
  // While the unsaved-edits question is up, keys answer it and nothing reaches the view.
  if (unsaved_.active()) {
    keyAnswer = unsaved_.keyAnswer(input);
    input.clear();
    navigation_.releaseKeys();  // a release of a held key would not reach it
  }
  // While Ctrl+O's focus is on its way to the path field, typed keys belong to the field, not to shortcuts.
  // Orbit and pan speeds follow the image as shown, up to the view's size (a zoomed-in image turns no slower).
  const float navigationHeight = l.imageHeight > 0.0f ? std::min(l.imageHeight, l.viewHeight) : l.viewHeight;
  navigation_.handle(input, io.WantCaptureMouse, io.WantCaptureKeyboard || filePanel_.focusOpenPath, l.viewHeight,
                     navigationHeight, session(), shortcuts);
  applyImageView(shortcuts, l);
  l = layout();
  if (shortcuts.focusOpen) {
    // Before the panels are drawn, so the Scene panel already holds this frame's typed characters.
    filePanel_.focusOpenPath = true;
    filePanel_.focusFrames = 0;
    filePanel_.typeAhead.clear();
    filePanel_.enterAhead = false;
  }
  // An Enter typed before the field has the focus is held until the field has the characters (drawScenePanel).
  if (filePanel_.focusOpenPath)
    for (const InputEvent& e : input)
      if (e.kind == InputEvent::Kind::Key && e.pressed && (e.key == GLFW_KEY_ENTER || e.key == GLFW_KEY_KP_ENTER))
        filePanel_.enterAhead = true;
  return shortcuts;
}

void ViewerApp::applyImageView(const Shortcuts& shortcuts, const ViewerLayout& l) {
  if (shortcuts.toggleImageView) setImageView(!display_.imageView);
  if (!session()) return;
  // Fit, 1:1, zoom and pan are of the file's image: from the window view they go to the image view.
  if (ImageViewController::asked(shortcuts) && !display_.imageView) setImageView(true);
  if (!display_.imageView) return;
  const Camera& file = session()->committedEdits().camera;
  if (imageView_.applyShortcuts(shortcuts, l, file.width, file.height)) framesToDraw_ = kSettleFrames;
}

// Edits into restarts: the drag state, the window view's size, this frame's edits, then a measurement asked for.
void ViewerApp::commitFrame(const ViewerLayout& l) {
  const ImGuiIO& io = ImGui::GetIO();
  if (navigation_.dragging()) marksUntil_ = Clock::now() + kMarksAfterNavigation;
  // Hold the coarse level while the user drags the view or a value.
  render_.setInteractive(navigation_.dragging() || (ImGui::IsAnyItemActive() && io.MouseDown[0]));
  if (SceneSession* s = session()) {
    // One drag, or one value held or typed in a panel, is one undo step.
    s->setGesture(navigation_.dragging() || ImGui::IsAnyItemActive());
    s->setViewport(windowViewSize(l, display_.imageView));
  }
  commitEdits();
  updateTitle();
  // Measured once this frame's edits are committed: what is about to be rendered.
  if (tradeoff_.startRequested(session(), whyNoTradeoff(), sceneSerial(), l.viewWidth, l.viewHeight))
    render_.restart(nullptr);  // the measurement gets the cores; the image on screen stays
}

void ViewerApp::drawImageArea(const ViewerLayout& l) {
  const ProgressiveFrame* frame = render_.haveFrame() ? &render_.frame() : nullptr;
  const ImageTexture* instead = compare_.shownInstead(frame, navigation_.flipHeld(), display_.mapping);
  // Again after the panels and the script: an exposure or gamma changed this frame shows this frame.
  const ImageTexture& shown = instead ? *instead : render_.texture(display_.mapping);
  if (!shown.empty()) imageView_.drawImage(shown, l, instead ? nullptr : frame);
  if (!saves_.viewSaveRequested()) drawSceneMarks(l);
  // Saving the view as seen: the image area alone, no overlay over it.
  if (saves_.viewSaveRequested()) return;
  const SceneSession* s = load_.session();
  const Camera rendered = s ? s->renderedCamera() : Camera{};
  const ReadoutSource readout{render_.frame(), compare_.comparison(), s ? &s->committedEdits().camera : nullptr,
                              s ? &rendered : nullptr, display_.imageView,
                              s && render_.frameIsOfSize(rendered.width, rendered.height)};
  drawOverlays(l, imageView_.readout(l, readout));
}

void ViewerApp::finishFrame(const ViewerLayout& l) {
  int framebufferWidth = 0, framebufferHeight = 0;
  window_.framebufferSize(framebufferWidth, framebufferHeight);
  glViewport(0, 0, framebufferWidth, framebufferHeight);
  glClearColor(0.09f, 0.09f, 0.1f, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT);
  imgui_.render();
  saves_.writeCaptures(framebufferWidth, framebufferHeight, l, render_.haveFrame(), scenePath());
  window_.swapBuffers();
  tradeoff_.frameDrawn();
  render_.markDrawn();
  if (finalFrameShown()) render_.announceFinal();
  // Ctrl+S pressed while refining saves once the file's image is ready (the final pass on screen in the image
  // view; rendered in the background after it in the window view).
  saves_.pollPending(frameSaveContext());
}

void ViewerApp::drawFrame() {
  render_.texture(display_.mapping);  // before the layout, which fits the texture's size
  std::vector<InputEvent> input = window_.takeInput();
  std::vector<int> touched;
  for (const InputEvent& e : input)
    if (e.kind == InputEvent::Kind::Key) touched.push_back(e.key);
  imgui_.beginFrame(quickPresses(input), touched);
  ViewerLayout l = layout();
  std::optional<UnsavedPrompt::Answer> keyAnswer;
  const Shortcuts shortcuts = handleInput(l, std::move(input), keyAnswer);
  if (script_ && script_->running()) script_->step(*this);

  PanelActions actions;
  drawPanels(l, actions);
  if (const std::optional<UnsavedPrompt::Answer> answer = unsaved_.draw(keyAnswer)) answerUnsaved(*answer);
  apply(actions, shortcuts);
  if (shortcuts.click) pickAt(shortcuts.click->first, shortcuts.click->second, shortcuts.doubleClick, l);
  dollyAtCursor(shortcuts, l);
  commitFrame(l);
  drawImageArea(l);
  finishFrame(l);
}

}  // namespace rayview
