#pragma once
// Private: constructors of the traversal back-ends, chosen by buildAccel().

#include <memory>

#include "rayview/accel.h"

namespace rayview {

std::unique_ptr<Accel> makeEmbreeAccel(const SceneGeometry& scene, const glm::dvec3& origin, BuildProgress progress,
                                       void* progressUser);
std::unique_ptr<Accel> makeReferenceAccel(const SceneGeometry& scene, const glm::dvec3& origin,
                                          BuildProgress progress, void* progressUser);

}  // namespace rayview
