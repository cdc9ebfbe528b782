// The viewer's panel column, the overlays over the image area, and what the panels and keys ask for.
#include <algorithm>
#include <cstdio>

#include <imgui.h>

#include "rayview/scene_writer.h"
#include "scene_pick.h"
#include "view_habits.h"
#include "viewer_app.h"

namespace rayview {

void ViewerApp::drawPanels(const ViewerLayout& l, PanelActions& actions) {
  const ImGuiWindowFlags flags = ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse |
                                 ImGuiWindowFlags_NoTitleBar | ImGuiWindowFlags_NoBringToFrontOnFocus;
  ImGui::SetNextWindowPos(ImVec2(0.0f, 0.0f));
  if (display_.hidePanels) {
    // The image has the whole window; one small button brings the column back.
    if (ImGui::Begin("##showpanels", nullptr, flags | ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoSavedSettings))
    {
      if (ImGui::Button("Show panels (F9)")) actions.togglePanels = true;
      ImGui::SameLine();
      ImGui::TextDisabled("F1: keys");
    }
    ImGui::End();
  } else {
    ImGui::SetNextWindowSize(ImVec2(l.panelWidth, l.viewHeight));
    if (ImGui::Begin("rayview", nullptr, flags)) drawPanelColumn(l, actions);
    ImGui::End();
  }
}

void ViewerApp::drawPanelColumn(const ViewerLayout&, PanelActions& actions) {
  if (ImGui::SmallButton("Hide panels (F9)")) actions.togglePanels = true;
  // Text, not a button: where it stands, a click did nothing before, and tools that click there rely on it.
  ImGui::SameLine();
  ImGui::TextDisabled("F1 or ?: keys and mouse");
  ImGui::PushItemWidth(-ImGui::GetFontSize() * 9.0f);  // room for the labels on the right
  SceneSession* s = session();
  const SceneInfo info{scenePath().empty() ? (s ? "default scene (embedded)" : "no scene yet") : scenePath(),
                       load_.warnings(),
                       isModelFile(scenePath()) ? std::optional(load_.modelUp()) : std::nullopt};
  drawScenePanel(filePanel_, load_.recent(), info, load_.progress(), actions);
  saves_.showProgress(s);
  drawSavePanel(filePanel_, render_.haveFrame(), actions);
  if (s) {
    drawCameraPanel(*s, cameraPanel_, editProblem_, actions);
    drawRenderSettingsPanel(*s, display_);
    drawLightsPanel(s->edits(), s->bounds().radius());
    const std::optional<std::size_t> picked =
        s->selection() ? std::optional<std::size_t>(s->selection()->material) : std::nullopt;
    drawMaterialsPanel(s->edits(), s->loaded().hasAnyTexture(), picked, s->takeMaterialReveal());
    const std::string why = whyNoTradeoff();
    drawTradeoffPanel(tradeoff_.panel(), s->edits(), s->settings(), why.empty(), why, actions);
  }
  const bool haveFrame = render_.haveFrame();
  const std::optional<ImageError> figures = finalComparison();
  const CompareInfo compare{compare_.comparison(), haveFrame ? render_.frame().width : 0,
                            haveFrame ? render_.frame().height : 0, figures.has_value(),
                            figures ? figures->cameraMismatch : std::string()};
  drawComparePanel(compare_.panel(), compare, actions);
  ImGui::PopItemWidth();
}

void ViewerApp::apply(const PanelActions& actions, const Shortcuts& shortcuts) {
  SceneSession* s = session();
  if (actions.open) openFromUser(*actions.open);
  if (actions.reload || shortcuts.reload) reload();
  if (actions.modelUp) setModelUp(*actions.modelUp);
  if (actions.saveFrame || shortcuts.saveFrame) saves_.saveFrameReporting(frameSaveContext());
  if (actions.saveView) saves_.requestViewSave({}, true);  // drawn and read back next frame
  if (actions.saveSceneNumbered || shortcuts.saveScene) saves_.saveSceneReporting(s, scenePath(), {});
  if (actions.saveSceneAs) saves_.saveSceneReporting(s, scenePath(), *actions.saveSceneAs);
  if (actions.cancelTradeoff) cancelTradeoff();
  if (actions.measureTradeoff) measureTradeoff(*actions.measureTradeoff);
  if (actions.loadReference) loadReference(*actions.loadReference);
  if (actions.toggleDifference || shortcuts.toggleDifference) compare_.toggleDifference();
  if (actions.applyTradeoffRow) tradeoff_.applyRow(s, *actions.applyTradeoffRow);
  if (shortcuts.quit) quitFromUser();
  if (s && shortcuts.undo) s->undo();
  if (s && shortcuts.redo) s->redo();
  if (actions.togglePanels || shortcuts.togglePanels) {
    display_.hidePanels = !display_.hidePanels;
    std::printf("panels %s\n", display_.hidePanels ? "hidden" : "shown");
    std::fflush(stdout);
  }
  if (s && (actions.frameScene || shortcuts.frameScene)) s->navigate([&](OrbitCamera& o) { o.frame(s->framingBounds()); });
  if (s && (actions.resetCamera || shortcuts.resetCamera)) s->navigate([](OrbitCamera& o) { o.reset(); });
  if (shortcuts.toggleHelp) display_.showHelp = !display_.showHelp;
  if (shortcuts.closeHelp) display_.showHelp = false;
  applyHabits(shortcuts);
}

void ViewerApp::applyHabits(const Shortcuts& shortcuts) {
  SceneSession* s = session();
  // Home: everything, ground planes too (F leaves them out).
  if (s && shortcuts.frameAll) s->navigate([&](OrbitCamera& o) { o.frame(s->bounds()); });
  if (shortcuts.toggleFullscreen) {
    window_.toggleFullscreen();
    std::printf("fullscreen %s\n", window_.fullscreen() ? "on" : "off");
    std::fflush(stdout);
  }
  if (shortcuts.exposureSteps != 0) {
    display_.mapping.exposureStops = stepExposure(display_.mapping.exposureStops, shortcuts.exposureSteps);
    std::printf("exposure %s\n", formatNumber(display_.mapping.exposureStops).c_str());
    std::fflush(stdout);
  }
}

void ViewerApp::dollyAtCursor(const Shortcuts& shortcuts, const ViewerLayout& l) {
  SceneSession* s = session();
  if (!s || shortcuts.dollySteps == 0.0) return;
  const auto [x, y] = shortcuts.dollyAt;
  const Camera camera = s->renderedCamera();
  std::optional<ImagePixel> pixel;
  if (l.inView(x, y))
    pixel = ImagePlacement::pixelAt({l.imageX, l.imageY, l.imageWidth, l.imageHeight}, camera.width, camera.height,
                                    screenPixelCentre(x, l.framebufferScale), screenPixelCentre(y, l.framebufferScale));
  const std::optional<PickResult> hit = pixel ? s->hitRendered(pixel->i, pixel->j) : std::nullopt;
  // Toward what is under the cursor; over the background, toward the pivot as before.
  if (hit) s->navigate([&](OrbitCamera& o) { o.dollyToward(hit->point, shortcuts.dollySteps); });
  else s->navigate([&](OrbitCamera& o) { o.dolly(shortcuts.dollySteps); });
  marksUntil_ = Clock::now() + kMarksAfterNavigation;
}

void ViewerApp::pickAt(double x, double y, bool doubleClick, const ViewerLayout& l) {
  SceneSession* s = session();
  // Only on the image area, and there on the image as placed (fitted or zoomed).
  if (!s || !l.inView(x, y)) return;
  // A pixel of the image the session renders (the window view's or the file's): the ray through it.
  const Camera camera = s->renderedCamera();
  const std::optional<ImagePixel> pixel =
      ImagePlacement::pixelAt({l.imageX, l.imageY, l.imageWidth, l.imageHeight}, camera.width, camera.height,
                              screenPixelCentre(x, l.framebufferScale), screenPixelCentre(y, l.framebufferScale));
  if (!pixel) return;
  const std::optional<PickResult> pick = s->pickRendered(pixel->i, pixel->j);
  std::printf("%s\n", pick ? describePick(*pick, s->loaded(), s->edits()).c_str() : "picked nothing");
  std::fflush(stdout);
  if (pick && doubleClick) s->navigate([&](OrbitCamera& o) { o.setPivot(pick->point); });
}

void ViewerApp::updateTitle() {
  std::string title = "rayview - " + (scenePath().empty() ? std::string("default scene") : scenePath());
  if (session() && session()->differsFromFile()) title += " *";
  if (title != shownTitle_) window_.setTitle(shownTitle_ = title);
}

void ViewerApp::openFromUser(const std::string& path) {
  if (!session() || !session()->unsaved()) return open(path);
  unsaved_.ask(UnsavedPrompt::Action::Open, path);
  framesToDraw_ = kSettleFrames;
}

void ViewerApp::quitFromUser() {
  if (!session() || !session()->unsaved()) return quit(0);
  unsaved_.ask(UnsavedPrompt::Action::Quit, {});
  framesToDraw_ = kSettleFrames;
}

void ViewerApp::answerUnsaved(UnsavedPrompt::Answer answer) {
  framesToDraw_ = kSettleFrames;
  if (answer == UnsavedPrompt::Answer::Cancel) return;
  if (answer == UnsavedPrompt::Answer::Save) {
    saves_.saveSceneReporting(session(), scenePath(), {});
    if (filePanel_.lastSaveFailed) return;  // the edits are still unsaved: stay
  }
  if (unsaved_.action() == UnsavedPrompt::Action::Quit) quit(0);
  else open(unsaved_.openPath());
}

}  // namespace rayview
