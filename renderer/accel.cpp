#include "rayview/accel.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "accel_backends.h"

namespace rayview {

namespace {

std::string scientific(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.3g", v);
  return buffer;
}

double largestComponent(const glm::dvec3& v) { return std::max({std::fabs(v.x), std::fabs(v.y), std::fabs(v.z)}); }

}  // namespace

std::string embreeRangeProblem(const Scene& scene, const glm::dvec3& origin) {
  // Rays start at the eye or on a surface, pushed off it by <shadowrayepsilon> (or a relative offset far
  // below 1 %); their directions are unit vectors except camera rays, which go through the near plane.
  // Non-finite vertices are left out: their triangles have no surface, and Embree skips invalid boxes.
  double reach = largestComponent(scene.camera.position - origin);
  const char* what = "the camera";
  auto consider = [&](const glm::dvec3& p, const char* name) {
    const double r = largestComponent(p - origin);
    if (std::isfinite(r) && r > reach) reach = r, what = name;
  };
  for (const Triangle& t : scene.triangles)
    for (std::uint32_t v : t.vertex)
      if (v < scene.vertices.size()) consider(scene.vertices[v], "a vertex");
  for (const PointLight& light : scene.pointLights) consider(light.position, "a point light");
  for (const TriangularLight& light : scene.triangularLights)
    for (const glm::dvec3* p : {&light.vertex1, &light.vertex2, &light.vertex3}) consider(*p, "a triangular light");
  const double epsilon = scene.shadowRayEpsilon.value_or(0.0);
  const Camera& c = scene.camera;
  const double nearPlane = c.nearDistance + std::max({std::fabs(c.left), std::fabs(c.right), std::fabs(c.bottom),
                                                      std::fabs(c.top)});
  const double limit = kEmbreeCoordinateLimit;
  if (!(nearPlane <= limit))
    return "the camera's near plane reaches " + scientific(nearPlane) + ", beyond the " + scientific(limit) +
           " Embree can represent";
  if (!(reach * (1.0 + 0x1p-10) + epsilon <= limit))
    return what + std::string(" is ") + scientific(reach) + " from the camera" +
           (epsilon > 0.0 ? " (with <shadowrayepsilon> " + scientific(epsilon) + ")" : std::string()) +
           ", beyond the " + scientific(limit) + " Embree can represent";
  return {};
}

std::unique_ptr<Accel> buildAccel(const Scene& scene, AccelKind kind, const glm::dvec3& origin,
                                  BuildProgress progress, void* progressUser) {
#ifdef RAYVIEW_HAVE_EMBREE
  if (kind == AccelKind::Embree && embreeRangeProblem(scene, origin).empty())
    return makeEmbreeAccel(scene, origin, progress, progressUser);
#endif
  (void)kind;
  return makeReferenceAccel(scene, origin, progress, progressUser);
}

}  // namespace rayview
