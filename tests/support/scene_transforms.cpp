#include "support/scene_transforms.h"

#include <algorithm>

namespace rayview::testing {

void scaleScene(Scene& scene, double factor) {
  for (glm::dvec3& v : scene.vertices) v *= factor;
  Camera& c = scene.camera;
  c.position *= factor;
  c.left *= factor;
  c.right *= factor;
  c.bottom *= factor;
  c.top *= factor;
  c.nearDistance *= factor;
  const float intensityFactor = static_cast<float>(factor * factor);
  for (PointLight& light : scene.lights.of<PointLight>()) {
    light.position *= factor;
    light.intensity *= intensityFactor;
  }
  for (TriangularLight& light : scene.lights.of<TriangularLight>()) {
    light.vertex1 *= factor;
    light.vertex2 *= factor;
    light.vertex3 *= factor;
    light.intensity *= intensityFactor;
  }
  if (scene.shadowRayEpsilon) *scene.shadowRayEpsilon *= factor;
}

void translateScene(Scene& scene, const glm::dvec3& offset) {
  for (glm::dvec3& v : scene.vertices) v += offset;
  scene.camera.position += offset;
  for (PointLight& light : scene.lights.of<PointLight>()) light.position += offset;
  for (TriangularLight& light : scene.lights.of<TriangularLight>()) {
    light.vertex1 += offset;
    light.vertex2 += offset;
    light.vertex3 += offset;
  }
}

void reduceResolution(Scene& scene, int divisor) {
  scene.camera.width = std::max(1, scene.camera.width / divisor);
  scene.camera.height = std::max(1, scene.camera.height / divisor);
}

}  // namespace rayview::testing
