#pragma once
// A scene ready to render: the parsed scene plus what is built from its geometry once per load (the
// traversal structure and float shading geometry). Camera, lights and materials can be edited on a copy of
// `scene` without rebuilding anything; only a change of geometry needs a new PreparedScene.

#include <functional>
#include <memory>

#include "rayview/accel.h"
#include "rayview/scene.h"
#include "rayview/tracer.h"

namespace rayview {

struct PreparedGeometry {
  std::shared_ptr<const Scene> source;  // the scene the geometry came from (its meshes are read while tracing)
  std::unique_ptr<Accel> accel;
  ShadingGeometry shading;
  double buildMs = 0.0;
};

// Builds the accelerator relative to the scene's camera position. Returns nullptr when `progress` cancels.
std::shared_ptr<const PreparedGeometry> prepareGeometry(std::shared_ptr<const Scene> scene, AccelKind kind,
                                                        BuildProgress progress = nullptr, void* progressUser = nullptr);
// Same, on a copy of `scene`.
std::shared_ptr<const PreparedGeometry> prepareGeometry(const Scene& scene, AccelKind kind,
                                                        BuildProgress progress = nullptr, void* progressUser = nullptr);

// A copy of everything but the meshes (vertices, triangles, normals, texture coordinates, texture): what an
// edit changes. Cheap whatever the scene's size; render it with a PreparedGeometry of the full scene.
Scene parametersOf(const Scene& scene);

}  // namespace rayview
