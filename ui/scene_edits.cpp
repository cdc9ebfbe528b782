#include "scene_edits.h"

#include <cmath>

#include "rayview/camera_rays.h"
#include "rayview/knobs.h"

namespace rayview {
namespace {

bool finite(const glm::dvec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }
bool finite(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

template <typename T>
int findById(const std::vector<T>& items, const std::string& id) {
  for (std::size_t i = 0; i < items.size(); ++i)
    if (items[i].id == id) return static_cast<int>(i);
  return -1;
}

}  // namespace

EditEffect classifyEdit(const SceneParameters& before, const RenderSettings& beforeSettings,
                        const SceneParameters& after, const RenderSettings& afterSettings) {
  if (beforeSettings.accel != afterSettings.accel) return EditEffect::Rebuild;
  if (!(before == after) || !(beforeSettings == afterSettings)) return EditEffect::Restart;
  return EditEffect::None;
}

std::string editProblem(const SceneParameters& edits, const RenderSettings& settings) {
  const Camera& c = edits.camera;
  if (!finite(c.position) || !finite(c.gaze) || !finite(c.up)) return "camera: numbers must be finite";
  if (std::string problem = cameraProblem(c); !problem.empty()) return "camera: " + problem;
  if (c.width > kMaxViewerImageSide || c.height > kMaxViewerImageSide ||
      static_cast<long long>(c.width) * c.height > kMaxViewerImagePixels)
    return "camera: resolution too large for the viewer (at most " + std::to_string(kMaxViewerImageSide) +
           " per side; use rayview render for bigger images)";
  // The knobs' own limits (the panel and scripts keep to them; a value set some other way is caught here).
  for (const Knob& knob : knobTable()) {
    const int value = knob.get(edits, settings);
    if (!knob.isChoice() && (value < knob.min || value > knob.max))
      return std::string(knob.label) + " must be from " + std::to_string(knob.min) + " to " + std::to_string(knob.max);
  }
  std::string lightProblem;
  edits.lights.forEachType([&](const auto& list) {
    using Light = LightOf<decltype(list)>;
    for (const Light& light : list)
      for (const auto& field : Light::fields())
        if (lightProblem.empty() && !(field.point ? finite(light.*field.point) : finite(light.*field.intensity)))
          lightProblem = std::string(Light::kType.noun) + " " + light.id + ": numbers must be finite";
  });
  if (!lightProblem.empty()) return lightProblem;
  for (const Material& m : edits.materials)
    if (!finite(m.ambient) || !finite(m.diffuse) || !finite(m.specular) || !finite(m.mirror) ||
        !std::isfinite(m.phongExponent) || !std::isfinite(m.textureFactor) || !finite(m.baseColor))
      return "material " + m.id + ": numbers must be finite";
  return {};
}

int findMaterial(const SceneParameters& edits, const std::string& id) { return findById(edits.materials, id); }
bool sameApartFromTheView(const SceneParameters& a, const SceneParameters& b) {
  SceneParameters moved = b;
  moved.camera.position = a.camera.position;
  moved.camera.gaze = a.camera.gaze;
  moved.camera.up = a.camera.up;
  return a == moved;
}

}  // namespace rayview
