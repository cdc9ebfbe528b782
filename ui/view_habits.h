#pragma once
// The small rules behind habits users bring from other viewers (Blender, tev, F3D): exposure keys, a reference
// image found beside the scene, where a point of the scene is on screen. No GL, no ImGui.

#include <optional>
#include <string>

#include <glm/vec3.hpp>

#include "display_mapping.h"
#include "rayview/scene.h"

namespace rayview {

// E and Shift+E change the exposure by this many stops, within the slider's limits (display_mapping.h).
inline constexpr double kExposureKeyStops = 0.5;
double stepExposure(double stops, int steps);

// The course's reference image kept beside the scene: SCENE.png (or SCENE.ppm) next to SCENE.xml; nullopt when
// there is none (or no scene file).
std::optional<std::string> referenceBeside(const std::string& scenePath);

// Where world point `p` is drawn, seen by `camera` (its whole near plane mapped onto the rectangle at x, y of
// width x height, window units); nullopt when it is behind the eye.
struct ScreenPoint {
  float x = 0.0f, y = 0.0f;
};
std::optional<ScreenPoint> projectToScreen(const glm::dvec3& p, const Camera& camera, float x, float y, float width,
                                           float height);

}  // namespace rayview
