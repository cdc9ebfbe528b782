// The unsaved-edits question before quitting or opening another scene.
#include "unsaved_prompt.h"

#include <cstdio>

#include <GLFW/glfw3.h>
#include <imgui.h>

namespace rayview {

void UnsavedPrompt::ask(Action action, const std::string& path) {
  if (!asked_) {
    std::printf("unsaved edits: save, discard or cancel?\n");
    std::fflush(stdout);
  }
  asked_ = action;
  action_ = action;
  path_ = path;
}

std::optional<UnsavedPrompt::Answer> UnsavedPrompt::keyAnswer(const std::vector<InputEvent>& input) const {
  if (!asked_) return std::nullopt;
  for (const InputEvent& e : input) {
    if (e.kind != InputEvent::Kind::Key || !e.pressed || e.repeat) continue;
    if (e.key == GLFW_KEY_S || e.key == GLFW_KEY_ENTER) return Answer::Save;
    if (e.key == GLFW_KEY_D) return Answer::Discard;
    if (e.key == GLFW_KEY_ESCAPE || e.key == GLFW_KEY_C) return Answer::Cancel;
  }
  return std::nullopt;
}

std::optional<UnsavedPrompt::Answer> UnsavedPrompt::draw(std::optional<Answer> keyAnswer) {
  if (!asked_) return std::nullopt;
  constexpr const char* kTitle = "Unsaved edits";
  if (!ImGui::IsPopupOpen(kTitle)) ImGui::OpenPopup(kTitle);
  const ImGuiIO& io = ImGui::GetIO();
  ImGui::SetNextWindowPos(ImVec2(io.DisplaySize.x * 0.5f, io.DisplaySize.y * 0.5f), ImGuiCond_Always, ImVec2(0.5f, 0.5f));
  std::optional<Answer> answer = keyAnswer;
  if (ImGui::BeginPopupModal(kTitle, nullptr, ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoMove)) {
    ImGui::TextUnformatted("The scene has edits that are not saved.");
    if (*asked_ == Action::Quit) ImGui::TextUnformatted("Save them (as a new numbered file) before quitting?");
    else ImGui::Text("Save them (as a new numbered file) before opening %s?", path_.c_str());
    if (ImGui::Button("Save (S)")) answer = Answer::Save;
    ImGui::SameLine();
    if (ImGui::Button("Discard (D)")) answer = Answer::Discard;
    ImGui::SameLine();
    if (ImGui::Button("Cancel (Esc)")) answer = Answer::Cancel;
    if (answer) ImGui::CloseCurrentPopup();
    ImGui::EndPopup();
  }
  if (!answer) return std::nullopt;
  asked_.reset();
  const char* names[] = {"save", "discard", "cancel"};
  std::printf("answered %s\n", names[static_cast<int>(*answer)]);
  std::fflush(stdout);
  return answer;
}

}  // namespace rayview
