// The "Camera" panel: the numeric camera of the scene format, plus frame / reset.
#include <algorithm>
#include <cfloat>
#include <cmath>

#include <imgui.h>

#include "panels.h"
#include "widgets.h"

namespace rayview {

std::string resolutionRefusal(int width, int height) {
  if (width >= 1 && height >= 1) return {};
  return "resolution " + std::to_string(width) + " x " + std::to_string(height) +
         " not applied: each side must be at least 1 pixel";
}

void drawCameraPanel(SceneSession& session, CameraPanelState& state, const std::string& problem, PanelActions& actions) {
  if (!ImGui::CollapsingHeader("Camera", ImGuiTreeNodeFlags_DefaultOpen)) return;
  hintText("Left drag: orbit. Middle or Shift+left drag: pan. Wheel: dolly.");
  if (ImGui::Button("Frame scene (F)")) actions.frameScene = true;
  ImGui::SameLine();
  if (ImGui::Button("Reset to file (R)")) actions.resetCamera = true;

  Camera& c = session.edits().camera;
  // Drag speeds relative to the scene's size, so that both a 1e-3 and a 1e3 scene move comfortably.
  const double radius = session.bounds().radius() > 0.0 ? session.bounds().radius() : 1.0;
  editPoint("Position", c.position, radius * 0.005);
  editPoint("Gaze", c.gaze, 0.005);
  editPoint("Up", c.up, 0.005);
  double nearPlane[4] = {c.left, c.right, c.bottom, c.top};
  if (editDoubles("Near plane", nearPlane, 4, 0.002 * std::max(std::abs(c.right - c.left), 1e-9), -DBL_MAX,
                  DBL_MAX)) {
    c.left = nearPlane[0];
    c.right = nearPlane[1];
    c.bottom = nearPlane[2];
    c.top = nearPlane[3];
  }
  if (ImGui::IsItemHovered()) tooltip("left, right, bottom, top (<nearplane> l r b t)");
  editDoubles("Near distance", &c.nearDistance, 1, 0.002 * std::max(c.nearDistance, 1e-9), DBL_MIN, DBL_MAX);

  int resolution[2] = {c.width, c.height};
  const bool entered = ImGui::InputInt2("Resolution", resolution, ImGuiInputTextFlags_EnterReturnsTrue);
  // A side of 0 or less is refused and said, never made 1 (the image would silently become a pixel wide).
  if (entered) state.resolutionProblem = resolutionRefusal(resolution[0], resolution[1]);
  if (entered && state.resolutionProblem.empty()) {
    resolution[0] = std::min(resolution[0], kMaxViewerImageSide);
    resolution[1] = std::min(resolution[1], kMaxViewerImageSide);
    const bool widthChanged = resolution[0] != c.width;
    if (state.keepFieldOfView) {
      session.setResolutionKeepingAspect(resolution[0], resolution[1], widthChanged);
    } else {
      // The near plane widens or narrows about its centre so pixels stay square.
      c.width = resolution[0];
      c.height = resolution[1];
      const double centre = 0.5 * (c.left + c.right);
      const double halfWidth = 0.5 * std::abs(c.top - c.bottom) * c.width / c.height;
      c.left = centre - halfWidth;
      c.right = centre + halfWidth;
    }
  }
  if (!state.resolutionProblem.empty()) problemText(state.resolutionProblem);
  ImGui::Checkbox("Keep field of view", &state.keepFieldOfView);
  if (ImGui::IsItemHovered())
    tooltip("On: a new width changes the height (and the other way round) to keep the near plane's aspect.\n"
                      "Off: the near plane widens or narrows to the new aspect.");
  problemText(problem);
}

}  // namespace rayview
