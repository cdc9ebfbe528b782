#pragma once
// A scene's geometry ready to render: the geometry plus what is built from it once per load (the traversal
// structure and the shading geometry, both relative to an origin). Any SceneParameters can be rendered with
// it (see Tracer): an edit of the camera, lights or materials never rebuilds anything.

#include <functional>
#include <memory>
#include <string>

#include "rayview/accel.h"
#include "rayview/cut_outs.h"
#include "rayview/scene.h"
#include "rayview/tracer.h"

namespace rayview {

struct PreparedGeometry {
  std::shared_ptr<const SceneGeometry> source;  // the geometry it came from (read while tracing)
  // The scene's cut-outs (null when it has none, and for bare geometry, which has no materials): before `accel`,
  // which reads it, so that it is destroyed after it.
  std::unique_ptr<const CutOuts> cutOuts;
  std::unique_ptr<Accel> accel;
  ShadingGeometry shading;
  double buildMs = 0.0;
  // Why the reference BVH was built where Embree was asked for (embreeRangeProblem), "" otherwise: set by the
  // overloads that take a Scene.
  std::string accelFallback;
};

// What a BVH is built for. Every caller names it: it chooses the build.
enum class BvhBuild {
  // Many renders from any camera (the viewer, the trade-off measurement, tests): Embree's full build (the packet BVH
  // for small scenes).
  Interactive,
  // One image of the scene's own camera (`rayview render`, a frame of a turntable or batch): as Interactive, except
  // that Embree builds at its quick quality when that image casts few camera rays a triangle (embreeLayoutFor): the
  // same answers sooner. Needs the scene's camera: with bare geometry it builds as Interactive.
  OneImage,
  // Less memory (rayview/lean_memory.h): rayview's packet BVH with leaves of up to kLeanLeafTriangles, the same
  // answers, slower rays.
  Lean,
};

// Builds the accelerator relative to `origin` (the camera's position: coordinates relative to the camera,
// taken in double before anything becomes float, SPEC section 6). Returns nullptr when `progress` cancels.
// `materials`: the parameters whose materials give the cut-outs (null: none, drawn opaque).
std::shared_ptr<const PreparedGeometry> prepareGeometry(std::shared_ptr<const SceneGeometry> geometry,
                                                        const glm::dvec3& origin, AccelKind kind, BvhBuild build,
                                                        BuildProgress progress = nullptr, void* progressUser = nullptr,
                                                        const SceneParameters* materials = nullptr);
// The same for a loaded scene, relative to its camera, with its cut-outs (rayview/cut_outs.h, from the materials as
// they are now: an edit of a material's cut-out needs a new build); shares `scene` (no copy of its meshes). Embree is
// used only when every ray of the scene stays in its range (embreeRangeProblem), else the reference BVH and
// `accelFallback` says why.
std::shared_ptr<const PreparedGeometry> prepareGeometry(std::shared_ptr<const Scene> scene, AccelKind kind,
                                                        BvhBuild build, BuildProgress progress = nullptr,
                                                        void* progressUser = nullptr);
// Same, on a copy of the scene's geometry.
std::shared_ptr<const PreparedGeometry> prepareGeometry(const Scene& scene, AccelKind kind, BvhBuild build,
                                                        BuildProgress progress = nullptr, void* progressUser = nullptr);

}  // namespace rayview
