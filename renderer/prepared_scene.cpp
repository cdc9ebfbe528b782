#include "rayview/prepared_scene.h"

#include <chrono>

namespace rayview {

std::shared_ptr<const PreparedGeometry> prepareGeometry(std::shared_ptr<const SceneGeometry> geometry,
                                                        const glm::dvec3& origin, AccelKind kind,
                                                        BuildProgress progress, void* progressUser) {
  const auto start = std::chrono::steady_clock::now();
  auto prepared = std::make_shared<PreparedGeometry>();
  prepared->accel = buildAccel(*geometry, availableAccel(kind), origin, progress, progressUser);
  if (!prepared->accel) return nullptr;
  prepared->shading = prepareShadingGeometry(*geometry, origin);
  prepared->source = std::move(geometry);
  prepared->buildMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return prepared;
}

namespace {

// Embree for a scene whose rays all stay within its range (its lights and epsilon included), else the
// reference BVH.
AccelKind accelFor(const Scene& scene, AccelKind kind) {
  if (availableAccel(kind) == AccelKind::Embree && !embreeRangeProblem(scene, scene, scene.camera.position).empty())
    return AccelKind::Reference;
  return kind;
}

}  // namespace

std::shared_ptr<const PreparedGeometry> prepareGeometry(std::shared_ptr<const Scene> scene, AccelKind kind,
                                                        BuildProgress progress, void* progressUser) {
  const glm::dvec3 origin = scene->camera.position;
  kind = accelFor(*scene, kind);
  return prepareGeometry(std::shared_ptr<const SceneGeometry>(scene, &scene->geometry()), origin, kind, progress,
                         progressUser);
}

std::shared_ptr<const PreparedGeometry> prepareGeometry(const Scene& scene, AccelKind kind, BuildProgress progress,
                                                        void* progressUser) {
  return prepareGeometry(std::make_shared<const SceneGeometry>(scene.geometry()), scene.camera.position,
                         accelFor(scene, kind), progress, progressUser);
}

}  // namespace rayview
