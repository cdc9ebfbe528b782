#include "widgets.h"

#include <algorithm>
#include <cfloat>
#include <cmath>

#include <imgui.h>

namespace rayview {
namespace {

constexpr const char* kNumberFormat = "%.6g";
constexpr ImGuiSliderFlags kExact = ImGuiSliderFlags_NoRoundToFormat;

// Drag speed proportional to the value's size, so tiny and huge scenes both drag comfortably.
float radianceSpeed(const Color& c) { return std::max(0.5f, 0.004f * std::max({c.x, c.y, c.z})); }

// The last item (a whole group, such as InputInt's field, buttons and label) is under the mouse. ImGui's
// IsItemHovered() is false over a group's text field (the field, not the group, is the hovered item), so the
// knobs' tooltips never showed over their fields.
bool itemRectHovered() {
  return ImGui::IsWindowHovered(ImGuiHoveredFlags_AllowWhenBlockedByActiveItem) &&
         ImGui::IsMouseHoveringRect(ImGui::GetItemRectMin(), ImGui::GetItemRectMax());
}

}  // namespace

bool editPoint(const char* label, glm::dvec3& value, double speed) {
  return ImGui::DragScalarN(label, ImGuiDataType_Double, &value.x, 3, static_cast<float>(speed), nullptr, nullptr,
                            kNumberFormat, kExact);
}

bool editDoubles(const char* label, double* values, int count, double speed, double minimum, double maximum) {
  return ImGui::DragScalarN(label, ImGuiDataType_Double, values, count, static_cast<float>(speed), &minimum, &maximum,
                            kNumberFormat, kExact | ImGuiSliderFlags_AlwaysClamp);
}

bool editRadiance(const char* label, Color& value) {
  return ImGui::DragFloat3(label, &value.x, radianceSpeed(value), 0.0f, FLT_MAX, "%.5g", kExact);
}

bool editCoefficient(const char* label, Color& value) {
  return ImGui::ColorEdit3(label, &value.x, ImGuiColorEditFlags_Float | ImGuiColorEditFlags_HDR);
}

void problemText(const std::string& problem) {
  if (problem.empty()) return;
  ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1.0f, 0.45f, 0.4f, 1.0f));
  ImGui::TextWrapped("%s", problem.c_str());
  ImGui::PopStyleColor();
}

std::string counted(std::size_t count, const char* singular) {
  return std::to_string(count) + " " + singular + (count == 1 ? "" : "s");
}

void hintText(const char* text) {
  ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyleColorVec4(ImGuiCol_TextDisabled));
  ImGui::TextWrapped("%s", text);
  ImGui::PopStyleColor();
}

void tooltip(const std::string& text, float* shown) {
  const ImGuiIO& io = ImGui::GetIO();
  const ImGuiStyle& style = ImGui::GetStyle();
  // ImGui keeps a tooltip inside the window only when it fits: wrap it narrower than the window.
  const float width = std::min(35.0f * ImGui::GetFontSize(), io.DisplaySize.x - 4.0f * style.WindowPadding.x);
  ImGui::BeginTooltip();
  ImGui::PushTextWrapPos(ImGui::GetCursorPosX() + std::max(width, ImGui::GetFontSize()));
  ImGui::TextUnformatted(text.c_str());
  ImGui::PopTextWrapPos();
  if (shown) {
    const ImVec2 position = ImGui::GetWindowPos(), size = ImGui::GetWindowSize();
    shown[0] = position.x, shown[1] = position.y, shown[2] = position.x + size.x, shown[3] = position.y + size.y;
  }
  ImGui::EndTooltip();
}

bool editKnob(const Knob& knob, SceneParameters& parameters, RenderSettings& settings, const char* shownChoice) {
  const std::string label(knob.label);
  const int value = knob.get(parameters, settings);
  ImGui::BeginDisabled(!knob.matters(parameters, settings));
  int edited = value;
  bool changed = false;
  bool hovered = false;
  if (knob.isChoice()) {
    const bool open =
        ImGui::BeginCombo(label.c_str(), shownChoice ? shownChoice : std::string(knob.choices[value].label).c_str());
    hovered = itemRectHovered();
    if (open) {
      for (int i = 0; i < static_cast<int>(knob.choices.size()); ++i) {
        const bool selected = i == value;
        if (ImGui::Selectable(std::string(knob.choices[i].label).c_str(), selected)) {
          edited = i;
          changed = i != value;
        }
        if (selected) ImGui::SetItemDefaultFocus();
      }
      ImGui::EndCombo();
    }
  } else {
    if (ImGui::InputInt(label.c_str(), &edited)) {
      edited = std::clamp(edited, knob.min, knob.max);
      changed = edited != value;
    }
    hovered = itemRectHovered();
  }
  if (hovered)
    tooltip(std::string(knob.help) + " (--" + std::string(knob.name) + ", or `set " + std::string(knob.name) +
            "` in scripts)");
  ImGui::EndDisabled();
  if (changed) knob.set(parameters, settings, edited);
  return changed;
}

}  // namespace rayview
