#pragma once
// Private: constructors of the traversal back-ends, chosen by buildAccel().

#include <memory>

#include "rayview/accel.h"

namespace rayview {

std::unique_ptr<Accel> makeEmbreeAccel(const SceneGeometry& scene, const glm::dvec3& origin, BuildProgress progress,
                                       void* progressUser);
std::unique_ptr<Accel> makeReferenceAccel(const SceneGeometry& scene, const glm::dvec3& origin,
                                          BuildProgress progress, void* progressUser);

// `kind`, or the reference BVH when it is Embree and a vertex is beyond what Embree can represent (the
// geometry's part of embreeRangeProblem; buildAccel's check).
AccelKind accelWithinRange(const SceneGeometry& scene, AccelKind kind, const glm::dvec3& origin);

// buildAccel without its range check, for a caller that has made it (embreeRangeProblem covers it): the check
// reads every corner of every face, ~1 ms at 100 000 triangles, and a render made it three times.
std::unique_ptr<Accel> buildCheckedAccel(const SceneGeometry& scene, AccelKind kind, const glm::dvec3& origin,
                                         BuildProgress progress, void* progressUser);

}  // namespace rayview
