// The "Scene" and "Save" panels: opening (path field, recent files, reload) and saving.
#include <algorithm>
#include <filesystem>
#include <system_error>

#include <imgui.h>
#include <imgui_stdlib.h>

#include "panels.h"
#include "widgets.h"

namespace rayview {
namespace {

constexpr int kFocusRetryFrames = 4;
constexpr int kFocusGiveUpFrames = 30;

}  // namespace

void drawScenePanel(FilePanelState& state, const RecentFiles& recent, const SceneInfo& info, const LoadProgress& progress,
                    PanelActions& actions) {
  ImGuiIO& io = ImGui::GetIO();
  if (state.focusOpenPath) {
    // Ctrl+O was pressed and the field is not active yet: ImGui would drop what is typed meanwhile (no field
    // takes it), so hold it. The section opens even when the user had collapsed it.
    for (const ImWchar c : io.InputQueueCharacters) state.typeAhead.push_back(c);
    io.InputQueueCharacters.resize(0);
    ImGui::SetNextItemOpen(true);
  } else if (!state.typeAhead.empty()) {
    // The field became active last frame (its text selected): what was typed before goes in first.
    ImVector<ImWchar> arrived;
    arrived.swap(io.InputQueueCharacters);
    for (const unsigned int c : state.typeAhead) io.InputQueueCharacters.push_back(static_cast<ImWchar>(c));
    for (const ImWchar c : arrived) io.InputQueueCharacters.push_back(c);
    state.typeAhead.clear();
  }
  // An Enter typed before the field took the focus opens what was typed, once the field holds it (below).
  const bool enterAhead = !state.focusOpenPath && std::exchange(state.enterAhead, false);
  if (!ImGui::CollapsingHeader("Scene", ImGuiTreeNodeFlags_DefaultOpen)) return;
  ImGui::TextWrapped("%s", info.displayName.c_str());
  if (!info.warnings.empty()) {
    ImGui::PushID("warnings");
    if (ImGui::TreeNode("", "%zu warning%s", info.warnings.size(), info.warnings.size() == 1 ? "" : "s")) {
      const std::size_t listed = std::min(info.warnings.size(), kMaxListedWarnings);
      for (std::size_t i = 0; i < listed; ++i) ImGui::TextWrapped("%s", info.warnings[i].format().c_str());
      if (listed < info.warnings.size()) ImGui::TextDisabled("... and %zu more", info.warnings.size() - listed);
      ImGui::TreePop();
    }
    ImGui::PopID();
  }

  // ImGui activates a field the frame after the focus request; ask again now and then in case it was lost.
  if (state.focusOpenPath && state.focusFrames++ % kFocusRetryFrames == 0) ImGui::SetKeyboardFocusHere();
  ImGui::SetNextItemWidth(-ImGui::CalcTextSize("Open").x - ImGui::GetStyle().ItemSpacing.x -
                          ImGui::GetStyle().FramePadding.x * 2.0f);
  bool entered = ImGui::InputTextWithHint("##open", "scene.xml path (Ctrl+O)", &state.openPath,
                                          ImGuiInputTextFlags_EnterReturnsTrue | ImGuiInputTextFlags_AutoSelectAll);
  // An Enter that reaches the field before the held characters do waits for them.
  if (entered && state.focusOpenPath) entered = false, state.enterAhead = true;
  if (state.focusOpenPath && (ImGui::IsItemActive() || state.focusFrames > kFocusGiveUpFrames))
    state.focusOpenPath = false;  // the held characters are replayed next frame
  ImGui::SameLine();
  if ((ImGui::Button("Open") || entered || enterAhead) && !state.openPath.empty()) actions.open = state.openPath;

  if (ImGui::BeginCombo("Recent", recent.paths().empty() ? "(none yet)" : "choose a scene...")) {
    for (const std::string& path : recent.paths()) {
      // Looked up only while the list is open: a file deleted or moved since is shown greyed out.
      std::error_code error;
      if (!std::filesystem::exists(path, error)) {
        ImGui::Selectable((path + "  (missing)").c_str(), false, ImGuiSelectableFlags_Disabled);
      } else if (ImGui::Selectable(path.c_str())) {
        state.openPath = path;
        actions.open = path;
      }
    }
    ImGui::EndCombo();
  }
  if (info.modelUp) {
    // Which of the model's axes points up in the camera rayview makes for it (z for CAD and scans; --up).
    int up = *info.modelUp == ModelUpAxis::Z ? 1 : 0;
    ImGui::TextUnformatted("Up axis");
    ImGui::SameLine();
    const bool y = ImGui::RadioButton("Y", &up, 0);
    ImGui::SameLine();
    const bool z = ImGui::RadioButton("Z", &up, 1);
    if (y || z) actions.modelUp = up == 1 ? ModelUpAxis::Z : ModelUpAxis::Y;
  }
  if (ImGui::Button("Reload (F5)")) actions.reload = true;
  ImGui::SameLine();
  ImGui::Checkbox("Reload when the file changes", &state.reloadOnChange);
  hintText("Drop a scene file on the window to open it.");

  if (progress.busy) {
    const char* what = progress.building ? "building the BVH" : "reading the file";
    ImGui::ProgressBar(progress.building ? static_cast<float>(progress.fraction) : 0.0f, ImVec2(-1.0f, 0.0f), what);
  }
}

void drawSavePanel(FilePanelState& state, bool haveFrame, PanelActions& actions) {
  if (!ImGui::CollapsingHeader("Save", ImGuiTreeNodeFlags_DefaultOpen)) return;
  ImGui::BeginDisabled(!haveFrame);
  if (ImGui::Button("Save frame (Ctrl+S)")) actions.saveFrame = true;
  ImGui::EndDisabled();
  ImGui::SameLine();
  if (ImGui::Button("Save scene (Ctrl+Shift+S)")) actions.saveSceneNumbered = true;
  ImGui::BeginDisabled(!haveFrame);
  if (ImGui::Button("Save view as seen")) actions.saveView = true;
  ImGui::EndDisabled();
  if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled))
    tooltip("The image area exactly as it looks now (zoom, exposure and gamma, the reference or the "
                      "difference), without the panels and overlays: SCENE_view_001.png. Save frame is the render "
                      "itself.");
  ImGui::Checkbox("Frame as displayed", &state.saveFrameDisplayed);
  if (ImGui::IsItemHovered())
    tooltip("Off (the default): Save frame and Ctrl+S write the final pass raw, exactly as rayview render "
                      "writes it (SCENE_001.png). On: with the exposure and gamma of the Render panel applied, as the "
                      "image area shows it (SCENE_displayed_001.png).");
  ImGui::SetNextItemWidth(-ImGui::CalcTextSize("Save scene as").x - ImGui::GetStyle().ItemSpacing.x -
                          ImGui::GetStyle().FramePadding.x * 2.0f);
  const bool entered = ImGui::InputTextWithHint("##saveas", "edited.xml", &state.saveScenePath,
                                                ImGuiInputTextFlags_EnterReturnsTrue);
  ImGui::SameLine();
  if ((ImGui::Button("Save scene as") || entered) && !state.saveScenePath.empty()) actions.saveSceneAs = state.saveScenePath;
  // The writer writes the scene from its values: say so before the user loses the comments of a file they wrote.
  hintText("Written anew from the scene's values: the file's comments and layout are not kept.");
  if (state.lastSaveFailed) {
    problemText(state.lastSaved);  // red, whole, wrapped
  } else if (state.frameSavePending) {
    hintText(state.lastSaved.c_str());
  } else if (!state.lastSaved.empty()) {
    // Read-only text field: the path can be selected and copied.
    ImGui::SetNextItemWidth(-1.0f);
    ImGui::InputText("##saved", &state.lastSaved, ImGuiInputTextFlags_ReadOnly);
  }
}

}  // namespace rayview
