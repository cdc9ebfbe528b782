#include "rayview/prepared_scene.h"

#include <algorithm>
#include <chrono>

#include "accel_backends.h"
#include "rayview/lean_memory.h"

namespace rayview {

namespace {

using Clock = std::chrono::steady_clock;

// Builds with `kind` as given, except that Embree asked for a scene of up to kPacketBvhTriangles triangles gets the
// packet BVH (the same answers, none of Embree's start-up), and a lean build the packet BVH with bigger leaves
// (lean_memory.h): the caller has made Embree's range check (buildCheckedAccel). `pixels`, the one image's (OneImage
// only, else 0), lets Embree build quickly for a cheap image. `buildMs` counts from `start`, which includes that check.
// `parameters` (null for bare geometry) give the materials' cut-outs.
std::shared_ptr<PreparedGeometry> prepare(std::shared_ptr<const SceneGeometry> geometry,
                                          const SceneParameters* parameters, const glm::dvec3& origin, AccelKind kind,
                                          BvhBuild build, std::size_t pixels, BuildProgress progress,
                                          void* progressUser, Clock::time_point start) {
  auto prepared = std::make_shared<PreparedGeometry>();
  if (parameters) prepared->cutOuts = CutOuts::of(*parameters, *geometry);
  const CutOuts* cutOuts = prepared->cutOuts.get();
  const std::size_t triangles = geometry->triangles.size();
  if (kind == AccelKind::Embree && triangles <= kPacketBvhTriangles) kind = AccelKind::Packet;
  if (kind != AccelKind::Reference && build == BvhBuild::Lean)
    prepared->accel = makePacketBvhAccel(*geometry, origin, 0, kLeanLeafTriangles, cutOuts);
  else
    prepared->accel = buildCheckedAccel(*geometry, kind, origin, progress, progressUser, pixels, cutOuts);
  if (!prepared->accel) return nullptr;
  prepared->shading = prepareShadingGeometry(*geometry, origin);
  prepared->source = std::move(geometry);
  prepared->buildMs = std::chrono::duration<double, std::milli>(Clock::now() - start).count();
  return prepared;
}

// Embree for a scene whose rays all stay within its range (its lights and epsilon included), else the
// reference BVH, with the reason: one range check (it reads every corner of every face).
std::shared_ptr<const PreparedGeometry> prepareScene(std::shared_ptr<const SceneGeometry> geometry, const Scene& scene,
                                                     AccelKind kind, BvhBuild build, BuildProgress progress,
                                                     void* progressUser) {
  const auto start = Clock::now();
  kind = availableAccel(kind);
  std::string problem;
  if (kind != AccelKind::Reference) problem = embreeRangeProblem(scene, scene, scene.camera.position);
  // One image of the scene's own camera: its camera rays say whether the build outweighs it.
  const std::size_t pixels = build != BvhBuild::OneImage ? 0
                             : static_cast<std::size_t>(std::max(scene.camera.width, 0)) *
                                   static_cast<std::size_t>(std::max(scene.camera.height, 0));
  auto prepared = prepare(std::move(geometry), &scene.parameters(), scene.camera.position,
                          problem.empty() ? kind : AccelKind::Reference, build, pixels, progress, progressUser, start);
  if (prepared) prepared->accelFallback = std::move(problem);
  return prepared;
}

}  // namespace

std::shared_ptr<const PreparedGeometry> prepareGeometry(std::shared_ptr<const SceneGeometry> geometry,
                                                        const glm::dvec3& origin, AccelKind kind, BvhBuild build,
                                                        BuildProgress progress, void* progressUser,
                                                        const SceneParameters* materials) {
  const auto start = Clock::now();
  const AccelKind within = accelWithinRange(*geometry, availableAccel(kind), origin);
  return prepare(std::move(geometry), materials, origin, within, build, 0, progress, progressUser, start);
}

std::shared_ptr<const PreparedGeometry> prepareGeometry(std::shared_ptr<const Scene> scene, AccelKind kind,
                                                        BvhBuild build, BuildProgress progress, void* progressUser) {
  std::shared_ptr<const SceneGeometry> geometry(scene, &scene->geometry());
  return prepareScene(std::move(geometry), *scene, kind, build, progress, progressUser);
}

std::shared_ptr<const PreparedGeometry> prepareGeometry(const Scene& scene, AccelKind kind, BvhBuild build,
                                                        BuildProgress progress, void* progressUser) {
  return prepareScene(std::make_shared<const SceneGeometry>(scene.geometry()), scene, kind, build, progress,
                      progressUser);
}

}  // namespace rayview
