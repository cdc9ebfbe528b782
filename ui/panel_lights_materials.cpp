// The "Lights" and "Materials" panels: every light and material value the format has.
#include <imgui.h>

#include "panels.h"
#include "widgets.h"

namespace rayview {

void drawLightsPanel(SceneParameters& edits, double sceneRadius) {
  if (!ImGui::CollapsingHeader("Lights")) return;
  const double speed = (sceneRadius > 0.0 ? sceneRadius : 1.0) * 0.005;
  editRadiance("Ambient", edits.ambientLight);
  // Every light type (light_types.h), each value by its field table (light_type.h).
  int type = 0;
  edits.lights.forEachType([&](auto& list) {
    using Light = LightOf<decltype(list)>;
    ImGui::PushID(type++);
    for (std::size_t i = 0; i < list.size(); ++i) {
      Light& light = list[i];
      ImGui::PushID(static_cast<int>(i));
      if (ImGui::TreeNode(Light::kType.element.data(), "%s %s", Light::kType.title.data(), light.id.c_str())) {
        for (const auto& field : Light::fields()) {
          const std::string label(field.label);
          if (field.point) editPoint(label.c_str(), light.*field.point, speed);
          else editRadiance(label.c_str(), light.*field.intensity);
        }
        ImGui::TreePop();
      }
      ImGui::PopID();
    }
    ImGui::PopID();
  });
  if (edits.lights.empty()) hintText("This scene has no lights but the ambient light.");
}

void drawMaterialsPanel(SceneParameters& edits, bool hasTexture, std::optional<std::size_t> picked, bool reveal) {
  reveal = reveal && picked && *picked < edits.materials.size();
  if (reveal) ImGui::SetNextItemOpen(true);
  if (!ImGui::CollapsingHeader("Materials")) return;
  for (std::size_t i = 0; i < edits.materials.size(); ++i) {
    Material& m = edits.materials[i];
    ImGui::PushID(static_cast<int>(i));
    const bool isPicked = picked == i;
    if (isPicked && reveal) {
      ImGui::SetNextItemOpen(true);
      ImGui::SetScrollHereY(0.2f);
    }
    if (ImGui::TreeNode("material", isPicked ? "Material %s (picked)" : "Material %s", m.id.c_str())) {
      editCoefficient("Ambient", m.ambient);
      editCoefficient("Diffuse", m.diffuse);
      editCoefficient("Specular", m.specular);
      ImGui::DragFloat("Phong exponent", &m.phongExponent, 0.25f, 0.0f, 1e6f, "%.4g", ImGuiSliderFlags_NoRoundToFormat);
      editCoefficient("Mirror", m.mirror);
      if (hasTexture) ImGui::SliderFloat("Texture factor", &m.textureFactor, 0.0f, 1.0f, "%.3f");
      if (!m.metalRoughImage.empty()) {
        hintText("Where its metallic-roughness map applies, these three set the terms above.");
        editCoefficient("Base colour", m.baseColor);
        ImGui::SliderFloat("Metallic", &m.metallic, 0.0f, 1.0f, "%.3f", ImGuiSliderFlags_AlwaysClamp);
        ImGui::SliderFloat("Roughness", &m.roughness, 0.0f, 1.0f, "%.3f", ImGuiSliderFlags_AlwaysClamp);
      }
      ImGui::Checkbox("Two-sided (lit from behind too)", &m.twoSided);
      ImGui::TreePop();
    }
    ImGui::PopID();
  }
}

}  // namespace rayview
