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

bool editKnob(const Knob& knob, SceneParameters& parameters, RenderSettings& settings) {
  const std::string label(knob.label);
  const int value = knob.get(parameters, settings);
  ImGui::BeginDisabled(!knob.matters(parameters, settings));
  int edited = value;
  bool changed = false;
  bool hovered = false;
  if (knob.isChoice()) {
    const bool open = ImGui::BeginCombo(label.c_str(), std::string(knob.choices[value].label).c_str());
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
    ImGui::SetTooltip("%s (--%s, or `set %s` in scripts)", std::string(knob.help).c_str(), std::string(knob.name).c_str(),
                      std::string(knob.name).c_str());
  ImGui::EndDisabled();
  if (changed) knob.set(parameters, settings, edited);
  return changed;
}

}  // namespace rayview
