// The "Compare" panel: a reference image, the figures of the final pass against it, the difference view.
#include <cmath>
#include <cstdio>
#include <string>

#include <imgui.h>
#include <imgui_stdlib.h>

#include "panels.h"
#include "widgets.h"

namespace rayview {
namespace {

void figureRow(const char* name, const std::string& value) {
  ImGui::TableNextRow();
  ImGui::TableNextColumn();
  ImGui::TextUnformatted(name);
  ImGui::TableNextColumn();
  ImGui::TextUnformatted(value.c_str());
}

std::string percent(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3f %%", value);
  return text;
}

// The numbers `rayview compare` prints, with their names spelled out.
void figuresTable(const ImageError& figures) {
  const ImGuiTableFlags flags = ImGuiTableFlags_RowBg | ImGuiTableFlags_BordersInnerV | ImGuiTableFlags_SizingFixedFit;
  if (!ImGui::BeginTable("compare_figures", 2, flags)) return;
  figureRow("Exact", percent(figures.pctExact));
  figureRow("Within \u00b11", percent(pctWithin1(figures)));
  figureRow("Max difference", std::to_string(figures.maxChannelDifference) + " of 255");
  figureRow("PSNR", std::isinf(figures.psnrDb) ? std::string("infinite (identical)") : formatPsnr(figures.psnrDb) + " dB");
  ImGui::EndTable();
}

}  // namespace

void drawComparePanel(ComparePanelState& state, const CompareInfo& info, PanelActions& actions) {
  if (state.reveal) ImGui::SetNextItemOpen(true);
  const bool open = ImGui::CollapsingHeader("Compare");
  if (state.reveal) {
    ImGui::SetScrollHereY(0.0f);
    state.reveal = false;
  }
  if (!open) return;
  hintText("A reference image the size of the render (PNG or PPM): the course's, or your own ray tracer's output.");
  ImGui::SetNextItemWidth(-ImGui::CalcTextSize("Load").x - ImGui::GetStyle().ItemSpacing.x -
                          ImGui::GetStyle().FramePadding.x * 2.0f);
  const bool entered = ImGui::InputTextWithHint("##reference", "reference.png path", &state.path,
                                                ImGuiInputTextFlags_EnterReturnsTrue);
  ImGui::SameLine();
  if ((ImGui::Button("Load") || entered) && !state.path.empty()) actions.loadReference = state.path;
  if (state.filledBeside && !info.comparison.loaded())
    hintText("Filled in: this image sits beside the scene, with its name (the course's reference, kept next to its "
             "scene). Load (or Enter) compares.");

  const ReferenceComparison& comparison = info.comparison;
  problemText(comparison.loadError());
  if (!comparison.loaded()) return;

  ImGui::TextWrapped("Reference: %s (%d x %d)", comparison.path().c_str(), comparison.reference().width,
                     comparison.reference().height);
  bool difference = state.showDifference;
  if (ImGui::Checkbox("Difference view (D)", &difference)) actions.toggleDifference = true;
  hintText("Hold Space to see the reference. The difference view: identical pixels dimmed, off by 1 blue, 2 to 8 "
           "yellow, more than 8 red.");
  if (info.imageWidth > 0) {
    const std::string problem = comparison.sizeProblem(info.imageWidth, info.imageHeight);
    if (!problem.empty()) return problemText(problem);
  }
  if (!comparison.figures()) {
    hintText("Figures when the final pass is ready...");
    return;
  }
  figuresTable(*comparison.figures());
  if (!info.figuresCurrent) hintText("Of the last final pass; refining...");
  // The reference is of the file's camera: figures of another view compare different pictures.
  if (!info.cameraMismatch.empty()) problemText("Camera differs: " + info.cameraMismatch + " (Camera > Reset to file, or R, to match)");
}

}  // namespace rayview
