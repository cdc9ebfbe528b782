#include "support/numerics_scenes.h"

#include <atomic>
#include <chrono>
#include <cmath>
#include <mutex>
#include <numbers>

#include <glm/geometric.hpp>

#include "rayview/camera_rays.h"
#include "rayview/prepared_scene.h"
#include "rayview/thread_pool.h"
#include "support/scene_builder.h"
#include "support/test_meshes.h"

namespace rayview::testing {
namespace {

ThreadPool& pool() {
  static ThreadPool shared(2);
  return shared;
}

bool isFinite(const Color& c) { return std::isfinite(c.x) && std::isfinite(c.y) && std::isfinite(c.z); }

CheckedRender renderWith(const Scene& scene, const Accel& accel, const ShadingGeometry& shading,
                         const RenderSettings& settings) {
  const auto start = std::chrono::steady_clock::now();
  CheckedRender out;
  out.image = Image(scene.camera.width, scene.camera.height);
  const Tracer tracer(scene, accel, shading, settings);
  std::atomic<long> nonFinite{0};
  std::mutex countsMutex;
  pool().parallelFor(static_cast<std::size_t>(scene.camera.height), [&](std::size_t row) {
    RayCounts counts;
    const int j = static_cast<int>(row);
    for (int i = 0; i < scene.camera.width; ++i) {
      const Color c = tracer.tracePixel(i, j, counts);
      if (!isFinite(c)) ++nonFinite;
      std::uint8_t* pixel = out.image.pixel(i, j);
      for (int k = 0; k < 3; ++k) pixel[k] = quantizeChannel(c[k]);
    }
    std::lock_guard lock(countsMutex);
    out.rays += counts;
  });
  out.nonFinitePixels = nonFinite.load();
  out.ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return out;
}

}  // namespace

CheckedRender renderChecked(const Scene& scene, AccelKind accel, const RenderSettings& settings) {
  const auto prepared = prepareGeometry(scene, accel, BvhBuild::Interactive);
  return renderWith(scene, *prepared->accel, prepared->shading, settings);
}

CheckedRender renderCheckedWithOrigin(const Scene& scene, AccelKind accel, const glm::dvec3& origin,
                                      const RenderSettings& settings) {
  const auto built = buildAccel(scene, availableAccel(accel), origin);
  const ShadingGeometry shading = prepareShadingGeometry(scene, origin);
  return renderWith(scene, *built, shading, settings);
}

GrazingLightScene grazingLightScene(double scale, double elevationDegrees, int pixels, int n) {
  GrazingLightScene s;
  const glm::dmat3 rotation = genericRotation();
  s.planeCentre = glm::dvec3(0.31, -0.17, 0.23) * scale;
  s.planeNormal = rotation * glm::dvec3(0, 0, 1);
  const glm::dvec3 along = rotation * glm::dvec3(1, 0, 0), across = rotation * glm::dvec3(0, 1, 0);
  Scene& scene = s.scene;
  Material matte;
  matte.id = "matte";
  matte.diffuse = Color(1.0f);
  scene.materials.push_back(matte);
  addTessellatedPlane(scene, Placement{s.planeCentre, rotation, scale}, n, 0);

  // Camera 3 plane sizes above, 35 degrees off the normal, seeing only the middle of the plane.
  Camera& c = scene.camera;
  const glm::dvec3 viewFrom = glm::normalize(s.planeNormal * std::cos(0.61) + across * std::sin(0.61));
  c.position = s.planeCentre + 3.0 * scale * viewFrom;
  c.gaze = -viewFrom;
  c.up = along;
  c.left = c.bottom = -0.15 * scale;
  c.right = c.top = 0.15 * scale;
  c.nearDistance = scale;
  c.width = c.height = pixels;

  const double e = elevationDegrees * std::numbers::pi / 180.0;
  const double distance = 100.0 * scale;
  PointLight light;
  light.id = "grazing";
  light.position = s.planeCentre + distance * (std::cos(e) * along + std::sin(e) * s.planeNormal);
  light.intensity = Color(static_cast<float>(150.0 * distance * distance / std::sin(e)));
  scene.lights.of<PointLight>().push_back(light);
  return s;
}

double expectedGrazingRadiance(const GrazingLightScene& s, int i, int j) {
  const Camera& c = s.scene.camera;
  const glm::dvec3 d = pixelDirection(c, cameraBasis(c), i, j);
  const double t = glm::dot(s.planeCentre - c.position, s.planeNormal) / glm::dot(d, s.planeNormal);
  if (!(t > 0.0)) return -1.0;
  const glm::dvec3 x = c.position + t * d;
  const glm::dvec3 toLight = s.scene.lights.of<PointLight>()[0].position - x;
  const double d2 = glm::dot(toLight, toLight);
  const double cosine = std::max(0.0, glm::dot(s.planeNormal, toLight / std::sqrt(d2)));
  return static_cast<double>(s.scene.lights.of<PointLight>()[0].intensity.x) * cosine / d2;
}

Scene facingMirrorsScene(int maxDepth, int pixels) {
  Scene scene;
  scene.maxRayDepth = maxDepth;
  scene.ambientLight = Color(10.0f);
  Material mirror;
  mirror.id = "mirror";
  mirror.ambient = Color(0.1f);
  mirror.diffuse = Color(0.2f);
  mirror.mirror = Color(1.0f);
  scene.materials.push_back(mirror);
  addQuadFacingZ(scene, -100, -100, 100, 100, -1, 0);  // faces +z
  // The opposite mirror at z = +1, facing -z (clockwise seen from +z).
  const auto first = static_cast<std::uint32_t>(scene.vertices.size());
  scene.vertices.insert(scene.vertices.end(), {{-100, -100, 1}, {100, -100, 1}, {100, 100, 1}, {-100, 100, 1}});
  scene.meshes.push_back(Mesh{"back", 0, static_cast<std::uint32_t>(scene.triangles.size()), 2});
  for (auto [b, c] : {std::pair{2u, 1u}, std::pair{3u, 2u}}) {
    Triangle t;
    t.vertex[0] = first;
    t.vertex[1] = first + b;
    t.vertex[2] = first + c;
    scene.triangles.push_back(t);
  }
  PointLight light;
  light.id = "between";
  light.position = {0.3, 0.2, 0.0};
  light.intensity = Color(100.0f);
  scene.lights.of<PointLight>().push_back(light);
  Camera& c = scene.camera;
  c.position = {0, 0, 0};
  c.gaze = {0, 0, -1};
  c.left = c.bottom = -0.01;
  c.right = c.top = 0.01;
  c.nearDistance = 1.0;
  c.width = c.height = pixels;
  return scene;
}

}  // namespace rayview::testing
