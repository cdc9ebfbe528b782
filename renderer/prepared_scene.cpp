#include "rayview/prepared_scene.h"

#include <chrono>

namespace rayview {

std::shared_ptr<const PreparedGeometry> prepareGeometry(const Scene& scene, AccelKind kind, BuildProgress progress,
                                                        void* progressUser) {
  const auto start = std::chrono::steady_clock::now();
  auto prepared = std::make_shared<PreparedGeometry>();
  // Coordinates relative to the camera, taken in double before anything becomes float (SPEC section 6).
  const glm::dvec3 origin = scene.camera.position;
  prepared->accel = buildAccel(scene, availableAccel(kind), origin, progress, progressUser);
  if (!prepared->accel) return nullptr;
  prepared->shading = prepareShadingGeometry(scene, origin);
  prepared->buildMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return prepared;
}

}  // namespace rayview
