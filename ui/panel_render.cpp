// The "Render" panel (settings that restart the render) and the stats over the image (what it costs).
#include <algorithm>
#include <cstdio>
#include <iterator>
#include <string>

#include <imgui.h>

#include "panels.h"
#include "widgets.h"

namespace rayview {
namespace {

struct StatLine {
  const char* name;
  std::string value;
};

std::string formatted(const char* format, double value) {
  char text[64];
  std::snprintf(text, sizeof text, format, value);
  return text;
}

std::string millisecondsOrPending(double ms) {
  if (ms < 0.0) return "...";
  char text[32];
  std::snprintf(text, sizeof text, "%.1f ms", ms);
  return text;
}

}  // namespace

void drawRenderSettingsPanel(SceneSession& session, bool& showStats) {
  if (!ImGui::CollapsingHeader("Render", ImGuiTreeNodeFlags_DefaultOpen)) return;
  ImGui::Checkbox("Stats over the image", &showStats);  // display only: never restarts the render
  // Every render knob, as the knob table describes it; then what the scene file says that is not a knob.
  for (const Knob& knob : knobTable()) editKnob(knob, session.edits(), session.settings());
  editRadiance("Background", session.edits().background);
}

void drawStatsOverlay(const ViewerStats& s, float right, float bottom) {
  char level[48];
  if (s.stride <= 0) std::snprintf(level, sizeof level, "-");
  else if (s.stride == 1) std::snprintf(level, sizeof level, "full resolution%s", s.final ? " (final)" : "");
  else std::snprintf(level, sizeof level, "1/%d (blocks of %dx%d)", s.stride, s.stride, s.stride);
  const StatLine lines[] = {
      {"Preview level", level},
      {"Pass time", formatted("%.1f ms", s.passMs)},
      {"Speed", formatted("%.2f Mrays/s", s.megaRaysPerSecond)},
      {"Edit to first pass", millisecondsOrPending(s.editToFirstPassMs)},
      {"Edit to final pass", millisecondsOrPending(s.editToFinalPassMs)},
      {"Image", std::to_string(s.width) + " x " + std::to_string(s.height)},
      {"Triangles", std::to_string(s.triangles)},
      {"Read", formatted("%.1f ms", s.readMs)},
      {"BVH build", formatted("%.1f ms", s.bvhBuildMs)},
      {"Traversal", std::string(toString(s.accel))},
      {"Threads", std::to_string(s.threads)},
      {"Generation", std::to_string(s.generation)},
  };
  // Sized from this frame's text: auto-resizing would lag a frame, and an idle viewer draws few frames.
  float nameWidth = 0.0f, valueWidth = 0.0f;
  for (const StatLine& line : lines) {
    nameWidth = std::max(nameWidth, ImGui::CalcTextSize(line.name).x);
    valueWidth = std::max(valueWidth, ImGui::CalcTextSize(line.value.c_str()).x);
  }
  const ImGuiStyle& style = ImGui::GetStyle();
  const float gap = 2.0f * style.ItemSpacing.x;
  const ImVec2 size(nameWidth + gap + valueWidth + 2.0f * style.WindowPadding.x,
                    std::size(lines) * ImGui::GetTextLineHeightWithSpacing() - style.ItemSpacing.y +
                        2.0f * style.WindowPadding.y);
  ImGui::SetNextWindowPos(ImVec2(right, bottom), ImGuiCond_Always, ImVec2(1.0f, 1.0f));
  ImGui::SetNextWindowSize(size);
  ImGui::SetNextWindowBgAlpha(0.65f);
  const ImGuiWindowFlags flags = ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_NoSavedSettings |
                                 ImGuiWindowFlags_NoFocusOnAppearing | ImGuiWindowFlags_NoNav |
                                 ImGuiWindowFlags_NoInputs;
  if (ImGui::Begin("##stats", nullptr, flags)) {
    for (const StatLine& line : lines) {
      ImGui::TextUnformatted(line.name);
      ImGui::SameLine(style.WindowPadding.x + nameWidth + gap);
      ImGui::TextUnformatted(line.value.c_str());
    }
  }
  ImGui::End();
}

}  // namespace rayview
