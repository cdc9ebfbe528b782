#include "rayview/accel.h"

#include "accel_backends.h"

namespace rayview {

std::unique_ptr<Accel> buildAccel(const SceneGeometry& scene, AccelKind kind, const glm::dvec3& origin,
                                  BuildProgress progress, void* progressUser) {
#ifdef RAYVIEW_HAVE_EMBREE
  if (kind == AccelKind::Embree) return makeEmbreeAccel(scene, origin, progress, progressUser);
#endif
  (void)kind;
  return makeReferenceAccel(scene, origin, progress, progressUser);
}

}  // namespace rayview
