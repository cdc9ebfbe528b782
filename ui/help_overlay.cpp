// The help over the image (F1, ?): every row of the shortcut table, so what it lists is what the keys do.
#include <algorithm>

#include <imgui.h>

#include "panels.h"
#include "shortcut_table.h"

namespace rayview {

void drawHelpOverlay(bool& open, float x, float y, float width, float height) {
  if (!open) return;
  // Centred in the image area, at most its size; it scrolls when the area is too small for every row.
  const float helpWidth = std::min(width, ImGui::GetFontSize() * 36.0f);
  ImGui::SetNextWindowPos(ImVec2(x + 0.5f * width, y + 0.5f * height), ImGuiCond_Always, ImVec2(0.5f, 0.5f));
  ImGui::SetNextWindowSizeConstraints(ImVec2(helpWidth, 0.0f), ImVec2(helpWidth, height));
  ImGui::SetNextWindowBgAlpha(0.92f);
  const ImGuiWindowFlags flags = ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse |
                                 ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoSavedSettings |
                                 ImGuiWindowFlags_NoFocusOnAppearing;
  if (ImGui::Begin("Keys and mouse (F1 or ? hides, Esc too)", &open, flags)) {
    if (ImGui::BeginTable("##keys", 2, ImGuiTableFlags_RowBg | ImGuiTableFlags_SizingFixedFit)) {
      ImGui::TableSetupColumn("input", ImGuiTableColumnFlags_WidthFixed);
      ImGui::TableSetupColumn("does", ImGuiTableColumnFlags_WidthStretch);
      for (const ShortcutRow& row : shortcutTable()) {
        if (row.input[0] == '\0') continue;  // a second key of the row above, which names it
        ImGui::TableNextRow();
        ImGui::TableNextColumn();
        ImGui::TextUnformatted(row.input);
        ImGui::TableNextColumn();
        ImGui::PushTextWrapPos(0.0f);
        ImGui::TextUnformatted(row.does);
        ImGui::PopTextWrapPos();
      }
      ImGui::EndTable();
    }
    ImGui::PushTextWrapPos(0.0f);
    ImGui::TextDisabled("Keys typed into a field go to the field; Ctrl keys and F-keys still work there.");
    ImGui::PopTextWrapPos();
  }
  ImGui::End();
}

}  // namespace rayview
