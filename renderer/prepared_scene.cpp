#include "rayview/prepared_scene.h"

#include <chrono>

namespace rayview {

std::shared_ptr<const PreparedGeometry> prepareGeometry(const Scene& scene, AccelKind kind, BuildProgress progress,
                                                        void* progressUser) {
  return prepareGeometry(std::make_shared<const Scene>(scene), kind, progress, progressUser);
}

Scene parametersOf(const Scene& scene) {
  Scene parameters;
  parameters.maxRayDepth = scene.maxRayDepth;
  parameters.background = scene.background;
  parameters.shadowRayEpsilon = scene.shadowRayEpsilon;
  parameters.camera = scene.camera;
  parameters.ambientLight = scene.ambientLight;
  parameters.pointLights = scene.pointLights;
  parameters.triangularLights = scene.triangularLights;
  parameters.materials = scene.materials;
  parameters.meshes = scene.meshes;
  parameters.textureImage = scene.textureImage;
  parameters.sourcePath = scene.sourcePath;
  return parameters;
}

std::shared_ptr<const PreparedGeometry> prepareGeometry(std::shared_ptr<const Scene> sceneShared, AccelKind kind,
                                                        BuildProgress progress, void* progressUser) {
  const Scene& scene = *sceneShared;
  const auto start = std::chrono::steady_clock::now();
  auto prepared = std::make_shared<PreparedGeometry>();
  prepared->source = std::move(sceneShared);
  // Coordinates relative to the camera, taken in double before anything becomes float (SPEC section 6).
  const glm::dvec3 origin = scene.camera.position;
  prepared->accel = buildAccel(scene, availableAccel(kind), origin, progress, progressUser);
  if (!prepared->accel) return nullptr;
  prepared->shading = prepareShadingGeometry(scene, origin);
  prepared->buildMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return prepared;
}

}  // namespace rayview
