#include "scene_edits.h"

#include <cmath>

#include "rayview/camera_rays.h"

namespace rayview {
namespace {

bool finite(const glm::dvec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }
bool finite(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

bool samePointLight(const PointLight& a, const PointLight& b) {
  return a.id == b.id && a.position == b.position && a.intensity == b.intensity;
}

bool sameTriangularLight(const TriangularLight& a, const TriangularLight& b) {
  return a.id == b.id && a.vertex1 == b.vertex1 && a.vertex2 == b.vertex2 && a.vertex3 == b.vertex3 &&
         a.intensity == b.intensity;
}

bool sameMaterial(const Material& a, const Material& b) {
  return a.id == b.id && a.ambient == b.ambient && a.diffuse == b.diffuse && a.specular == b.specular &&
         a.phongExponent == b.phongExponent && a.mirror == b.mirror && a.textureFactor == b.textureFactor;
}

template <typename T, typename Same>
bool sameList(const std::vector<T>& a, const std::vector<T>& b, Same same) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (!same(a[i], b[i])) return false;
  return true;
}

template <typename T>
int findById(const std::vector<T>& items, const std::string& id) {
  for (std::size_t i = 0; i < items.size(); ++i)
    if (items[i].id == id) return static_cast<int>(i);
  return -1;
}

}  // namespace

SceneEdits editsOf(const Scene& scene) {
  SceneEdits e;
  e.maxRayDepth = scene.maxRayDepth;
  e.background = scene.background;
  e.camera = scene.camera;
  e.ambientLight = scene.ambientLight;
  e.pointLights = scene.pointLights;
  e.triangularLights = scene.triangularLights;
  e.materials = scene.materials;
  return e;
}

void applyEdits(const SceneEdits& edits, Scene& scene) {
  scene.maxRayDepth = edits.maxRayDepth;
  scene.background = edits.background;
  scene.camera = edits.camera;
  scene.ambientLight = edits.ambientLight;
  scene.pointLights = edits.pointLights;
  scene.triangularLights = edits.triangularLights;
  scene.materials = edits.materials;
}

bool sameCamera(const Camera& a, const Camera& b) {
  return a.position == b.position && a.gaze == b.gaze && a.up == b.up && a.left == b.left && a.right == b.right &&
         a.bottom == b.bottom && a.top == b.top && a.nearDistance == b.nearDistance && a.width == b.width &&
         a.height == b.height;
}

bool sameEdits(const SceneEdits& a, const SceneEdits& b) {
  return a.maxRayDepth == b.maxRayDepth && a.background == b.background && sameCamera(a.camera, b.camera) &&
         a.ambientLight == b.ambientLight && sameList(a.pointLights, b.pointLights, samePointLight) &&
         sameList(a.triangularLights, b.triangularLights, sameTriangularLight) &&
         sameList(a.materials, b.materials, sameMaterial);
}

EditEffect classifyEdit(const SceneEdits& before, const RenderSettings& beforeSettings, const SceneEdits& after,
                        const RenderSettings& afterSettings) {
  if (beforeSettings.accel != afterSettings.accel) return EditEffect::Rebuild;
  if (!sameEdits(before, after) || !(beforeSettings == afterSettings)) return EditEffect::Restart;
  return EditEffect::None;
}

std::string editProblem(const SceneEdits& edits, const RenderSettings& settings) {
  const Camera& c = edits.camera;
  if (!finite(c.position) || !finite(c.gaze) || !finite(c.up)) return "camera: numbers must be finite";
  if (std::string problem = cameraProblem(c); !problem.empty()) return "camera: " + problem;
  if (c.width > kMaxViewerImageSide || c.height > kMaxViewerImageSide ||
      static_cast<long long>(c.width) * c.height > kMaxViewerImagePixels)
    return "camera: resolution too large for the viewer (at most " + std::to_string(kMaxViewerImageSide) +
           " per side; use rayview render for bigger images)";
  if (edits.maxRayDepth < 0) return "max ray depth must not be negative";
  if (settings.lightSamples < 1 || settings.lightSamples > kMaxLightSamples)
    return "light samples must be from 1 to " + std::to_string(kMaxLightSamples);
  for (const PointLight& light : edits.pointLights)
    if (!finite(light.position) || !finite(light.intensity)) return "point light " + light.id + ": numbers must be finite";
  for (const TriangularLight& light : edits.triangularLights)
    if (!finite(light.vertex1) || !finite(light.vertex2) || !finite(light.vertex3) || !finite(light.intensity))
      return "triangular light " + light.id + ": numbers must be finite";
  for (const Material& m : edits.materials)
    if (!finite(m.ambient) || !finite(m.diffuse) || !finite(m.specular) || !finite(m.mirror) ||
        !std::isfinite(m.phongExponent) || !std::isfinite(m.textureFactor))
      return "material " + m.id + ": numbers must be finite";
  return {};
}

int findMaterial(const SceneEdits& edits, const std::string& id) { return findById(edits.materials, id); }
int findPointLight(const SceneEdits& edits, const std::string& id) { return findById(edits.pointLights, id); }
int findTriangularLight(const SceneEdits& edits, const std::string& id) { return findById(edits.triangularLights, id); }

}  // namespace rayview
