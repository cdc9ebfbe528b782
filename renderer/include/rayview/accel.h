#pragma once
// Ray traversal over the scene's triangles: closest hit and occlusion. Two back-ends: Embree (fast, float)
// and the reference BVH (double, independent of Embree). Both work in coordinates relative to `origin()`,
// a point fixed when the structure is built (the camera position), so that precision does not depend on
// how far the scene sits from the world origin.

#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "rayview/render_settings.h"
#include "rayview/scene.h"

namespace rayview {

inline constexpr std::uint32_t kNoTriangle = 0xFFFFFFFFu;

class CutOuts;  // rayview/cut_outs.h

// The most rays closestHits() and occludedMany() take at once: a 16-wide packet (docs/PERFORMANCE.md, "Packets").
inline constexpr int kRayPacket = 16;

// Rays are double end to end: both back-ends test triangles in double, so a ray's answer does not depend
// on which point its coordinates are relative to (the viewer's camera moves away from the origin the
// structure was built at; its final pass must still equal a headless render from the new camera).
struct Ray {
  glm::dvec3 origin{0.0};     // relative to Accel::origin()
  glm::dvec3 direction{0.0};  // need not be normalised; t is measured in units of |direction|
  double tNear = 0.0;
  double tFar = 0.0;
  std::uint32_t excludedTriangle = kNoTriangle;  // never reported as a hit (the triangle a ray leaves)
};

// A box relative to Accel::origin().
struct AccelBox {
  glm::dvec3 lower{std::numeric_limits<double>::infinity()};
  glm::dvec3 upper{-std::numeric_limits<double>::infinity()};
  bool empty() const { return !(lower.x <= upper.x); }
};

struct Hit {
  double t = 0.0;
  std::uint32_t triangle = 0;  // index into Scene::triangles
  double b1 = 0.0, b2 = 0.0;   // barycentric weights of vertex 1 and 2 (vertex 0 gets 1 - b1 - b2)
};

class Accel {
 public:
  virtual ~Accel() = default;
  virtual std::optional<Hit> closestHit(const Ray& ray) const = 0;
  virtual bool occluded(const Ray& ray) const = 0;  // any hit with tNear <= t <= tFar
  // hits[k] = closestHit(rays[k]) for k < count <= kRayPacket, exactly: a packet changes how fast the
  // answers come, never which (coherent rays, such as a block of camera rays, traverse together).
  virtual void closestHits(const Ray* rays, int count, std::optional<Hit>* hits) const {
    for (int k = 0; k < count; ++k) hits[k] = closestHit(rays[k]);
  }
  // answers[k] = occluded(rays[k]) for k < count <= kRayPacket, exactly (shadow rays toward one light).
  virtual void occludedMany(const Ray* rays, int count, bool* answers) const {
    for (int k = 0; k < count; ++k) answers[k] = occluded(rays[k]);
  }
  virtual AccelKind kind() const = 0;

  // The world point that ray coordinates are relative to.
  const glm::dvec3& origin() const { return origin_; }
  // Boxes that together hold every triangle a ray can hit (one whose corners are finite: every back-end leaves the
  // others out): a ray that misses them all hits nothing. Up to kAccelBoxes (one more when the meshes leave triangle
  // 0 out), each a run of triangles split at mesh starts, so a model and the floor under it get boxes of their own;
  // one box around every vertex above kBoxedTriangles, where the pass over the triangles would cost more than the
  // camera rays it spares.
  const std::vector<AccelBox>& boxes() const { return boxes_; }

 protected:
  Accel(const glm::dvec3& origin, const SceneGeometry& scene);

 private:
  glm::dvec3 origin_;
  std::vector<AccelBox> boxes_;
};

inline constexpr std::size_t kAccelBoxes = 16;
inline constexpr std::size_t kBoxedTriangles = 1u << 18;

// Progress in [0, 1]; return false to cancel the build (buildAccel then returns nullptr).
using BuildProgress = bool (*)(void* user, double fraction);

// Embree takes floats and refuses (asserts on, or silently drops the primitives of) anything beyond its
// FLT_LARGE, 1.844e18: rayview never hands it a coordinate, relative to the accel's origin, above this
// bound (docs/numerics.md, "What Embree can represent").
inline constexpr double kEmbreeCoordinateLimit = 1e18;

// Why Embree cannot trace `geometry` lit and seen as `parameters` say, with coordinates relative to `origin`
// ("" when it can): a vertex, a light, the camera or its near plane, or a vertex pushed off by
// <shadowrayepsilon> is beyond kEmbreeCoordinateLimit. Callers then choose the reference BVH.
std::string embreeRangeProblem(const SceneParameters& parameters, const SceneGeometry& geometry,
                               const glm::dvec3& origin);

// The Embree back-end when asked for and the geometry is within Embree's range, else the reference BVH.
// The accel may read `scene`'s arrays while tracing (the Embree back-end does, rather than copy them): the scene
// must outlive it and not change. `cutOuts` (null for none), when given, must outlive it too: a hit it hides is no
// hit, for closest hits and occlusion alike.
std::unique_ptr<Accel> buildAccel(const SceneGeometry& scene, AccelKind kind, const glm::dvec3& origin,
                                  BuildProgress progress = nullptr, void* progressUser = nullptr,
                                  const CutOuts* cutOuts = nullptr);

}  // namespace rayview
