// Windows that float over the image: the load error, the load progress, what the image area shows.
#include <cfloat>
#include <optional>

#include <imgui.h>

#include "panels.h"
#include "widgets.h"

namespace rayview {
namespace {

constexpr ImGuiWindowFlags kOverlayFlags = ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize |
                                           ImGuiWindowFlags_NoCollapse | ImGuiWindowFlags_AlwaysAutoResize |
                                           ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoFocusOnAppearing;

}  // namespace

float drawErrorOverlay(std::string& error, const std::string& stillShowing, float x, float y, float width) {
  if (error.empty()) return y;
  float below = y;
  ImGui::SetNextWindowPos(ImVec2(x, y));
  ImGui::SetNextWindowSizeConstraints(ImVec2(width, 0.0f), ImVec2(width, FLT_MAX));
  ImGui::PushStyleColor(ImGuiCol_WindowBg, ImVec4(0.35f, 0.06f, 0.06f, 0.94f));
  ImGui::PushStyleColor(ImGuiCol_TitleBg, ImVec4(0.55f, 0.08f, 0.08f, 1.0f));
  ImGui::PushStyleColor(ImGuiCol_TitleBgActive, ImVec4(0.55f, 0.08f, 0.08f, 1.0f));
  if (ImGui::Begin("Could not load the scene", nullptr, kOverlayFlags)) {
    ImGui::PushTextWrapPos(ImGui::GetCursorPosX() + width - 2.0f * ImGui::GetStyle().WindowPadding.x);
    ImGui::TextUnformatted(error.c_str());
    ImGui::PopTextWrapPos();
    if (!stillShowing.empty()) ImGui::TextDisabled("Still showing %s.", stillShowing.c_str());
    if (ImGui::Button("Dismiss")) error.clear();
    below = y + ImGui::GetWindowHeight() + ImGui::GetStyle().ItemSpacing.y;
  }
  ImGui::End();
  ImGui::PopStyleColor(3);
  return below;
}

float drawLoadingOverlay(const LoadProgress& progress, float x, float y, float width) {
  if (!progress.busy) return y;
  float below = y;
  ImGui::SetNextWindowPos(ImVec2(x, y));
  ImGui::SetNextWindowSizeConstraints(ImVec2(width, 0.0f), ImVec2(width, FLT_MAX));
  if (ImGui::Begin("##loading", nullptr, kOverlayFlags | ImGuiWindowFlags_NoTitleBar | ImGuiWindowFlags_NoInputs)) {
    ImGui::Text("Loading %s", progress.path.empty() ? "the default scene" : progress.path.c_str());
    ImGui::ProgressBar(progress.building ? static_cast<float>(progress.fraction) : 0.0f, ImVec2(-1.0f, 0.0f),
                       progress.building ? "building the BVH" : "reading the file");
    below = y + ImGui::GetWindowHeight() + ImGui::GetStyle().ItemSpacing.y;
  }
  ImGui::End();
  return below;
}

OverlaySize textOverlaySize(const std::string& text) {
  if (text.empty()) return {};
  const ImGuiStyle& style = ImGui::GetStyle();
  const ImVec2 size = ImGui::CalcTextSize(text.c_str());
  return {size.x + 2.0f * style.WindowPadding.x + 1.0f, size.y + 2.0f * style.WindowPadding.y, ImGui::GetTextLineHeight()};
}

void drawTextOverlay(const char* id, const std::string& text, const OverlayRect& at, float alpha,
                     std::optional<std::array<float, 3>> background) {
  ImGui::SetNextWindowPos(ImVec2(at.x, at.y));
  ImGui::SetNextWindowSize(ImVec2(at.width, at.height));
  if (background) ImGui::PushStyleColor(ImGuiCol_WindowBg, ImVec4((*background)[0], (*background)[1], (*background)[2], 1.0f));
  else ImGui::SetNextWindowBgAlpha(alpha);
  const ImGuiWindowFlags flags = ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_NoSavedSettings |
                                 ImGuiWindowFlags_NoFocusOnAppearing | ImGuiWindowFlags_NoNav | ImGuiWindowFlags_NoInputs;
  if (ImGui::Begin(id, nullptr, flags)) {
    ImGui::PushTextWrapPos(0.0f);
    ImGui::TextUnformatted(text.c_str());
    ImGui::PopTextWrapPos();
  }
  ImGui::End();
  if (background) ImGui::PopStyleColor();
}

}  // namespace rayview
