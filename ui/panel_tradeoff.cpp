// The "Speed vs accuracy" panel: measure what each knob costs and buys on the scene on screen (docs/tradeoff.md).
#include <algorithm>
#include <iterator>
#include <cstdint>
#include <cstdio>
#include <optional>
#include <string>

#include <imgui.h>

#include "panels.h"
#include "tradeoff_advice.h"
#include "tradeoff_task.h"
#include "widgets.h"

namespace rayview {
namespace {

const char* const kScaleNames[] = {"1/4 of the image", "1/2 of the image", "the whole image"};
static_assert(std::size(kScaleNames) == std::size(kTradeoffScales));

// The Apply button of a row that is a render setting: sets the knob as the Render panel does (an undoable
// edit that restarts the render). The row matching what the user has now says so instead.
void applyButton(const TradeoffPoint& p, std::size_t index, const SceneParameters& edits,
                 const RenderSettings& settings, PanelActions& actions) {
  const Knob* knob = tableKnob(p.setting.knob);
  const std::optional<int> value = knobValue(p.setting);
  if (!knob || !value) return;
  if (knob->get(edits, settings) == *value) {
    ImGui::TextDisabled("yours");
    return;
  }
  ImGui::PushID(static_cast<int>(index));
  if (ImGui::SmallButton("Apply")) actions.applyTradeoffRow = index;
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("Set %s to %s, as in Render (Ctrl+Z undoes it)", std::string(knob->label).c_str(),
                      settingLabel(p.setting).c_str());
  ImGui::PopID();
}

// One row per setting, under a row naming its knob with the Render panel's label.
void resultTable(const TradeoffReport& report, const SceneParameters& edits, const RenderSettings& settings,
                 PanelActions& actions) {
  const ImGuiTableFlags flags = ImGuiTableFlags_RowBg | ImGuiTableFlags_BordersInnerV | ImGuiTableFlags_SizingFixedFit;
  if (!ImGui::BeginTable("tradeoff", 5, flags)) return;
  ImGui::TableSetupColumn("setting", ImGuiTableColumnFlags_WidthStretch);
  ImGui::TableSetupColumn("ms");
  ImGui::TableSetupColumn("RMSE");
  ImGui::TableSetupColumn("% off>1");
  ImGui::TableSetupColumn("");
  ImGui::TableHeadersRow();
  const ImVec4 knobColour = ImGui::GetStyleColorVec4(ImGuiCol_PlotLinesHovered);
  for (std::size_t i = 0; i < report.points.size(); ++i) {
    const TradeoffPoint& p = report.points[i];
    const bool best = p.setting.knob == TradeoffKnob::BestImage;
    if (!best && (i == 0 || report.points[i - 1].setting.knob != p.setting.knob)) {
      ImGui::TableNextRow();
      ImGui::TableNextColumn();
      ImGui::TextColored(knobColour, "%s", std::string(knobLabel(p.setting.knob)).c_str());
    }
    ImGui::TableNextRow();
    ImGui::TableNextColumn();
    if (best) {
      ImGui::TextColored(knobColour, "%s", std::string(kBestImageLabel).c_str());
      if (ImGui::IsItemHovered()) tooltip(report.bestText.c_str());
    } else {
      ImGui::Indent();
      ImGui::TextUnformatted(settingLabel(p.setting).c_str());
      ImGui::Unindent();
    }
    ImGui::TableNextColumn();
    // Three digits: a coarse preview level takes hundredths of a millisecond.
    if (p.timeMs < 100.0) ImGui::Text("%.3g", p.timeMs);
    else ImGui::Text("%.0f", p.timeMs);
    ImGui::TableNextColumn();
    ImGui::Text("%.2f", p.error.rmse);
    ImGui::TableNextColumn();
    ImGui::Text("%.2f", p.error.pctOffByMoreThan1);
    ImGui::TableNextColumn();
    applyButton(p, i, edits, settings, actions);
  }
  ImGui::EndTable();
}

}  // namespace

void drawTradeoffPanel(TradeoffPanelState& state, const SceneParameters& edits, const RenderSettings& settings,
                       bool canMeasure, const std::string& why, PanelActions& actions) {
  const Camera& camera = edits.camera;
  if (state.reveal) ImGui::SetNextItemOpen(true);
  const bool open = ImGui::CollapsingHeader("Speed vs accuracy");
  if (state.reveal) {
    ImGui::SetScrollHereY(0.0f);  // the header at the top of the column: the result shows
    state.reveal = false;
  }
  if (!open) return;
  hintText("Renders every setting of each knob (Preview level, Max ray depth, Light samples, Traversal, Samples "
           "per pixel), the others as you have them, and compares it with the best image. The render pauses "
           "meanwhile; an edit cancels. Apply sets a row's value in Render.");

  ImGui::BeginDisabled(state.running);
  char preview[96];
  const double scale = kTradeoffScales[state.scaleIndex];
  std::snprintf(preview, sizeof preview, "%s (%d x %d)", kScaleNames[state.scaleIndex], scaledSide(camera.width, scale),
                scaledSide(camera.height, scale));
  if (ImGui::BeginCombo("Resolution", preview)) {
    for (int i = 0; i < static_cast<int>(std::size(kTradeoffScales)); ++i)
      if (ImGui::Selectable(kScaleNames[i], i == state.scaleIndex)) state.scaleIndex = i;
    ImGui::EndCombo();
  }
  ImGui::EndDisabled();

  if (state.running) {
    char label[160];
    std::snprintf(label, sizeof label, "%d / %d  %s", state.progress.rendersDone, state.progress.rendersPlanned,
                  state.progress.what.c_str());
    ImGui::ProgressBar(static_cast<float>(state.fraction), ImVec2(-ImGui::GetFontSize() * 5.0f, 0.0f), label);
    ImGui::SameLine();
    if (ImGui::Button("Cancel")) actions.cancelTradeoff = true;
  } else {
    ImGui::BeginDisabled(!canMeasure);
    if (ImGui::Button("Measure this scene")) actions.measureTradeoff = scale;
    ImGui::EndDisabled();
    if (!canMeasure && !why.empty()) {
      ImGui::SameLine();
      ImGui::TextDisabled("(%s)", why.c_str());
    }
  }
  if (!state.message.empty()) hintText(state.message.c_str());
  if (!state.report) return;

  const TradeoffReport& r = *state.report;
  ImGui::Text("%s, %d x %d, %zu settings, %.1f s", r.sceneName.c_str(), r.width, r.height, r.points.size(),
              r.totalMs / 1000.0);
  if (state.stale) ImGui::TextColored(ImVec4(0.95f, 0.75f, 0.3f, 1.0f), "Measured before the last edit or load.");
  // Every row varies one knob from these; the best image improves them.
  ImGui::PushTextWrapPos(0.0f);
  ImGui::TextUnformatted(("Measured against your settings: " + r.baselineText + ".").c_str());
  ImGui::PopTextWrapPos();
  hintText(("Best image: " + r.bestText + ".").c_str());
  ImGui::Checkbox("Plot over the image", &state.showPlot);
  const std::string advice = tradeoffAdvice(r);
  if (!advice.empty()) {
    ImGui::PushTextWrapPos(0.0f);
    ImGui::TextUnformatted(advice.c_str());
    ImGui::PopTextWrapPos();
  }
  if (const TradeoffPoint* suggested = tradeoffSuggestion(r)) {
    const std::string label = "Apply " + describeRow(suggested->setting);
    if (ImGui::Button(label.c_str()))
      actions.applyTradeoffRow = static_cast<std::size_t>(suggested - r.points.data());
  }
  for (const std::string& note : r.notes) hintText(note.c_str());
  resultTable(r, edits, settings, actions);
}

void drawTradeoffPlot(TradeoffPanelState& state, const ImageTexture& plot, float x, float y, float maxWidth,
                      float maxHeight) {
  if (!state.showPlot || !state.report || plot.empty()) return;
  // Plotted in screen units at the size of the image area: shown as is, or smaller if the window shrank.
  const ImGuiStyle& style = ImGui::GetStyle();
  const float chromeX = 2.0f * style.WindowPadding.x;
  const float chromeY = 2.0f * style.WindowPadding.y + ImGui::GetFrameHeight();  // title bar
  const float scale = std::min({1.0f, (maxWidth - chromeX) / plot.width(), (maxHeight - chromeY) / plot.height()});
  if (!(scale > 0.0f)) return;
  ImGui::SetNextWindowPos(ImVec2(x, y));
  const ImGuiWindowFlags flags = ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse |
                                 ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoSavedSettings |
                                 ImGuiWindowFlags_NoFocusOnAppearing;
  const std::string title = "Speed vs accuracy: " + state.report->sceneName +
                            (state.stale ? " (before the last edit)" : "") + "###tradeoff_plot";
  if (ImGui::Begin(title.c_str(), &state.showPlot, flags)) {
    ImGui::Image(reinterpret_cast<ImTextureID>(static_cast<std::intptr_t>(plot.id())),
                 ImVec2(plot.width() * scale, plot.height() * scale));
  }
  ImGui::End();
}

}  // namespace rayview
