// The "Lights" and "Materials" panels: every light and material value the format has.
#include <imgui.h>

#include "panels.h"
#include "widgets.h"

namespace rayview {

void drawLightsPanel(SceneParameters& edits, double sceneRadius) {
  if (!ImGui::CollapsingHeader("Lights")) return;
  const double speed = (sceneRadius > 0.0 ? sceneRadius : 1.0) * 0.005;
  editRadiance("Ambient", edits.ambientLight);
  for (std::size_t i = 0; i < edits.pointLights.size(); ++i) {
    PointLight& light = edits.pointLights[i];
    ImGui::PushID(static_cast<int>(i));
    if (ImGui::TreeNode("point", "Point light %s", light.id.c_str())) {
      editPoint("Position", light.position, speed);
      editRadiance("Intensity", light.intensity);
      ImGui::TreePop();
    }
    ImGui::PopID();
  }
  for (std::size_t i = 0; i < edits.triangularLights.size(); ++i) {
    TriangularLight& light = edits.triangularLights[i];
    ImGui::PushID(static_cast<int>(1000000 + i));
    if (ImGui::TreeNode("triangle", "Triangular light %s", light.id.c_str())) {
      editPoint("Vertex 1", light.vertex1, speed);
      editPoint("Vertex 2", light.vertex2, speed);
      editPoint("Vertex 3", light.vertex3, speed);
      editRadiance("Intensity", light.intensity);
      ImGui::TreePop();
    }
    ImGui::PopID();
  }
  if (edits.pointLights.empty() && edits.triangularLights.empty()) hintText("This scene has no point or triangular lights.");
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
      ImGui::TreePop();
    }
    ImGui::PopID();
  }
}

}  // namespace rayview
