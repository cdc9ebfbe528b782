// The overlays over the image area: the load error and progress, the trade-off plot, and, placed together so
// that none covers another, what the area shows, the last save's outcome, the stats and the pixel readout.
#include <algorithm>
#include <cstdio>

#include <glm/glm.hpp>
#include <imgui.h>

#include "view_habits.h"
#include "viewer_app.h"

namespace rayview {
namespace {

// The toast's colours: a save that worked, one that failed (opaque, so that they read over any image).
constexpr std::array<float, 3> kToastSaved{0.11f, 0.38f, 0.2f};
constexpr std::array<float, 3> kToastFailed{0.6f, 0.11f, 0.11f};

// Where `bounds` are on screen, seen by `camera` through the image placed at l's image rectangle; nullopt when
// they are wholly behind the camera.
std::optional<OverlayRect> onScreen(const Bounds& bounds, const Camera& camera, const ViewerLayout& l) {
  if (bounds.empty || camera.width <= 0 || camera.height <= 0) return std::nullopt;
  const glm::dvec3 forward = glm::normalize(camera.gaze);
  const glm::dvec3 right = glm::normalize(glm::cross(camera.gaze, camera.up));
  const glm::dvec3 up = glm::cross(right, forward);
  float x0 = 1e30f, y0 = 1e30f, x1 = -1e30f, y1 = -1e30f;
  for (int corner = 0; corner < 8; ++corner) {
    const glm::dvec3 p{corner & 1 ? bounds.max.x : bounds.min.x, corner & 2 ? bounds.max.y : bounds.min.y,
                       corner & 4 ? bounds.max.z : bounds.min.z};
    const glm::dvec3 d = p - camera.position;
    const double depth = glm::dot(d, forward);
    // A corner behind the eye: the bounds reach past the view's edges; take the whole image.
    if (depth <= 1e-9) return OverlayRect{l.imageX, l.imageY, l.imageWidth, l.imageHeight};
    const double s = glm::dot(d, right) * camera.nearDistance / depth;
    const double t = glm::dot(d, up) * camera.nearDistance / depth;
    const float x = l.imageX + static_cast<float>((s - camera.left) / (camera.right - camera.left)) * l.imageWidth;
    const float y = l.imageY + static_cast<float>((camera.top - t) / (camera.top - camera.bottom)) * l.imageHeight;
    x0 = std::min(x0, x), y0 = std::min(y0, y), x1 = std::max(x1, x), y1 = std::max(y1, y);
  }
  return OverlayRect{x0, y0, x1 - x0, y1 - y0};
}

// The full-resolution pass's bar, for a pass long enough to wait for.
constexpr float kProgressWidth = 300.0f;
constexpr float kSamplesProgressWidth = 420.0f;  // room for "samples 13/16, 81% of the render, 12 s left"
void drawPassProgress(const RenderProgress& progress, const OverlayRect& at) {
  ImGui::SetNextWindowPos(ImVec2(at.x, at.y));
  ImGui::SetNextWindowSize(ImVec2(at.width, at.height));
  ImGui::SetNextWindowBgAlpha(0.75f);
  const ImGuiWindowFlags flags = ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_NoSavedSettings |
                                 ImGuiWindowFlags_NoFocusOnAppearing | ImGuiWindowFlags_NoNav | ImGuiWindowFlags_NoInputs;
  if (ImGui::Begin("##pass_progress", nullptr, flags)) {
    const double fraction = progress.samplesTotal > 1 ? progress.renderFraction : progress.passFraction;
    ImGui::ProgressBar(static_cast<float>(fraction), ImVec2(-1.0f, 0.0f), describeProgress(progress).c_str());
  }
  ImGui::End();
}

std::string describe(const char* name, const std::optional<OverlayRect>& r) {
  if (!r) return std::string(" ") + name + "=none";
  char text[96];
  std::snprintf(text, sizeof text, " %s=%.0f,%.0f,%.0f,%.0f", name, r->x, r->y, r->width, r->height);
  return text;
}

}  // namespace

void ViewerApp::drawSceneMarks(const ViewerLayout& l) {
  const SceneSession* s = load_.session();
  if (!s || !compare_.viewLabel().empty()) return;  // over the reference or the difference they would mislead
  const Camera camera = s->renderedCamera();
  const auto project = [&](const glm::dvec3& p) -> std::optional<ImVec2> {
    const std::optional<ScreenPoint> q = projectToScreen(p, camera, l.imageX, l.imageY, l.imageWidth, l.imageHeight);
    return q ? std::optional<ImVec2>(ImVec2(q->x, q->y)) : std::nullopt;
  };
  ImDrawList* draw = ImGui::GetBackgroundDrawList();
  draw->PushClipRect(ImVec2(l.viewX, l.viewY), ImVec2(l.viewX + l.viewWidth, l.viewY + l.viewHeight), true);
  const float unit = ImGui::GetFontSize() * 0.5f;
  // The picked mesh: the outline of its bounding box.
  if (s->selection()) {
    const Bounds b = s->framingBounds();
    const auto corner = [&](int c) {
      return project({c & 1 ? b.max.x : b.min.x, c & 2 ? b.max.y : b.min.y, c & 4 ? b.max.z : b.min.z});
    };
    for (int c = 0; c < 8; ++c)
      for (const int bit : {1, 2, 4})
        if (!(c & bit))
          if (const auto a = corner(c), e = corner(c | bit); a && e) draw->AddLine(*a, *e, IM_COL32(255, 150, 30, 230), 2.0f);
  }
  const bool navigating = navigation_.dragging() || Clock::now() < marksUntil_;
  if (display_.alwaysShowMarks || navigating) {
    const ImU32 light = IM_COL32(255, 220, 60, 240);
    for (const PointLight& p : s->edits().lights.of<PointLight>())
      if (const auto q = project(p.position)) draw->AddCircle(*q, unit, light, 12, 2.0f);
    for (const TriangularLight& t : s->edits().lights.of<TriangularLight>())
      if (const auto a = project(t.vertex1), b = project(t.vertex2), c = project(t.vertex3); a && b && c)
        draw->AddTriangle(*a, *b, *c, light, 2.0f);
    if (const auto pivot = project(s->orbit().pivot())) {
      const ImU32 white = IM_COL32(255, 255, 255, 230);
      draw->AddLine(ImVec2(pivot->x - unit, pivot->y), ImVec2(pivot->x + unit, pivot->y), white, 2.0f);
      draw->AddLine(ImVec2(pivot->x, pivot->y - unit), ImVec2(pivot->x, pivot->y + unit), white, 2.0f);
    }
  }
  draw->PopClipRect();
}

void ViewerApp::drawOnTop(const ViewerLayout& l, float margin) {
  if (!endingMessage_.empty()) {
    const OverlaySize size = textOverlaySize(endingMessage_);
    const float width = std::min(size.width, l.viewWidth - 2.0f * margin);
    drawTextOverlay("##ending", endingMessage_,
                    {l.viewX + 0.5f * (l.viewWidth - width), l.viewY + 0.4f * l.viewHeight, width, size.height}, 1.0f,
                    kToastFailed);
  }
  // Over everything else: asked for, it is what the user is reading.
  drawHelpOverlay(display_.showHelp, l.viewX, l.viewY, l.viewWidth, l.viewHeight);
  if (display_.showHelp != helpPrinted_) {
    helpPrinted_ = display_.showHelp;
    std::printf("help %s\n", helpPrinted_ ? "shown" : "hidden");
    std::fflush(stdout);
  }
  if (!printOverlays_) return;
  if (!endingMessage_.empty() && !printedEnding_) {
    printedEnding_ = true;
    std::printf("ending shown\n");
    std::fflush(stdout);
  }
  if (!recovery_.buttons().empty() && recovery_.buttons() != printedRecovery_) {
    std::printf("recovery panel %s\n", recovery_.buttons().c_str());
    std::fflush(stdout);
  }
  printedRecovery_ = recovery_.buttons();
}

void ViewerApp::printProgress(const std::string& text) {
  if (text == printedProgress_) return;
  printedProgress_ = text;
  std::printf("progress %s\n", text.c_str());
  std::fflush(stdout);
}

std::vector<OverlayRect> ViewerApp::keepClear(const ViewerLayout& l) const {
  std::vector<OverlayRect> clear;
  // The reference or the difference on screen: the whole image is what the user looks at.
  if (!compare_.viewLabel().empty()) clear.push_back({l.imageX, l.imageY, l.imageWidth, l.imageHeight});
  const SceneSession* s = load_.session();
  if (s && s->selection())
    if (const std::optional<OverlayRect> picked = onScreen(s->framingBounds(), s->renderedCamera(), l)) clear.push_back(*picked);
  return clear;
}

void ViewerApp::drawOverlays(const ViewerLayout& l, const std::string& readout) {
  const ImGuiStyle& style = ImGui::GetStyle();
  const float margin = style.WindowPadding.x;
  const std::string stillShowing = session() ? describeScene(scenePath()) : std::string();
  const float belowError =
      drawErrorOverlay(load_.loadError(), stillShowing, l.viewX + margin, l.viewY + margin, l.viewWidth - 2.0f * margin);
  const float belowLoading = drawLoadingOverlay(load_.progress(), l.viewX + margin, belowError,
                                                std::min(l.viewWidth - 2.0f * margin, 480.0f * imgui_.layoutScale()));
  if (const std::optional<bool> restore = recovery_.draw(l.viewX + margin, belowLoading, l.viewWidth - 2.0f * margin))
    answerRecovery(*restore);
  drawTradeoffPlot(tradeoff_.panel(), tradeoff_.plot(), l.viewX + margin, belowLoading, l.viewWidth - 2.0f * margin,
                   l.viewY + l.viewHeight - margin - belowLoading);

  OverlayRequest q;
  q.view = {l.viewX, l.viewY, l.viewWidth, l.viewHeight};
  q.margin = margin;
  q.gap = style.ItemSpacing.y;
  q.topLeftHeight = std::max(0.0f, belowLoading - (l.viewY + margin));
  const std::string label = compare_.viewLabel();
  q.label = textOverlaySize(label);
  const SaveToast* toast = saves_.toast(Clock::now());
  if (toast) q.toast = textOverlaySize(toast->text);
  StatsText stats;
  if (display_.showStats && render_.haveFrame()) {
    stats = statsText(render_.stats());
    q.statsBox = statsBoxSize(stats);
    q.statsLine = textOverlaySize(stats.oneLine);
  }
  // In a small window the stats take one line, so they do not cover the image.
  const ImGuiIO& io = ImGui::GetIO();
  const float scale = imgui_.layoutScale();
  q.oneLine = display_.oneLineStats || io.DisplaySize.x < kCompactStatsWidth * scale ||
              io.DisplaySize.y < kCompactStatsHeight * scale;
  q.readout = textOverlaySize(readout);
  const std::optional<RenderProgress> progress = render_.fullPassProgress(Clock::now());
  if (progress) {
    const float width = progress->samplesTotal > 1 ? kSamplesProgressWidth : kProgressWidth;
    q.progress = {width * imgui_.layoutScale(), ImGui::GetFrameHeight() + 2.0f * style.WindowPadding.y, 0.0f};
  }
  q.keepClear = keepClear(l);
  const OverlayPlacement placed = placeOverlays(q);

  if (placed.label) drawTextOverlay("##view_label", label, *placed.label, 0.75f);
  if (placed.toast) drawTextOverlay("##toast", toast->text, *placed.toast, 1.0f, toast->failed ? kToastFailed : kToastSaved);
  if (placed.progress) drawPassProgress(*progress, *placed.progress);
  if (placed.stats) drawStatsOverlay(stats, *placed.stats, placed.statsOneLine);
  if (placed.readout) drawTextOverlay("##readout", readout, *placed.readout, 0.75f);
  drawOnTop(l, margin);
  if (!printOverlays_) return;
  if (placed.progress) printProgress(describeProgress(*progress));
  const std::string line = "overlays view=" + std::to_string(static_cast<int>(l.viewWidth)) + "x" +
                           std::to_string(static_cast<int>(l.viewHeight)) + describe("label", placed.label) +
                           describe("toast", placed.toast) + describe("progress", placed.progress) +
                           describe("stats", placed.stats) +
                           describe("readout", placed.readout) + (placed.statsOneLine ? " one_line=1" : " one_line=0");
  if (line == printedOverlays_) return;
  printedOverlays_ = line;
  std::printf("%s\n", line.c_str());
  std::fflush(stdout);
}

}  // namespace rayview
