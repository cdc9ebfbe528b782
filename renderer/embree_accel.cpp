// Embree 3 back-end: one triangle geometry holding every scene triangle, in float, relative to origin().
#include <embree3/rtcore.h>

#include <cstdio>
#include <limits>
#include <mutex>
#include <stdexcept>
#include <string>

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include <glm/common.hpp>

#include "accel_backends.h"
#include "float_steps.h"
#include "watertight_triangle.h"

namespace rayview {
namespace {

void reportDeviceError(void*, RTCError code, const char* message) {
  if (code == RTC_ERROR_CANCELLED) return;  // a build we cancelled on purpose
  std::fprintf(stderr, "rayview: Embree error %d: %s\n", static_cast<int>(code), message ? message : "");
}

// One device per process: creating a device starts Embree's worker threads, which is not free.
RTCDevice sharedDevice() {
  static RTCDevice device = [] {
    RTCDevice d = rtcNewDevice(nullptr);
    if (!d) throw std::runtime_error("Embree: cannot create a device");
    rtcSetDeviceErrorFunction(d, reportDeviceError, nullptr);
    return d;
  }();
  return device;
}

struct ProgressRelay {
  BuildProgress callback;
  void* user;
};

// The ray in double travels with the query: Embree traverses its float boxes with a float copy, and
// every candidate triangle is tested against the double ray. The closest hit so far is kept here too.
struct QueryContext {
  RTCIntersectContext context;  // first member: Embree hands back a pointer to it
  const Ray* ray;
  WatertightRay prepared;
  double tFar;                  // the ray's tFar, then the closest hit so far plus the tie band
  TriangleHit hit;
  unsigned triangle = RTC_INVALID_GEOMETRY_ID;
};

void initContext(QueryContext& c, const Ray& ray) {
  rtcInitIntersectContext(&c.context);
  c.ray = &ray;
  c.prepared = prepareWatertightRay(ray.origin, ray.direction);
  c.tFar = ray.tFar;
}

bool relayProgress(void* ptr, double fraction) {
  auto* relay = static_cast<ProgressRelay*>(ptr);
  return relay->callback(relay->user, fraction);
}

// Scenes from this many triangles get Embree's compact BVH layout (docs/PERFORMANCE.md, scale series).
constexpr std::size_t kCompactBvhTriangles = 500'000;

// Triangles as user primitives: Embree's BVH and traversal, the watertight test of watertight_triangle.h
// in double on the camera-relative double vertices (Embree 3's own robust test misses some rays through
// shared vertices; see docs/numerics.md).
// The scene's own arrays, borrowed (the scene outlives the accel: buildAccel's contract): no copy of the vertices
// or the indices, 24-84 B per triangle less (docs/PERFORMANCE.md). A triangle's corners relative to the origin are
// computed per test, in double, exactly as a stored relative copy held them.
struct TriangleData {
  const std::vector<glm::dvec3>* vertices = nullptr;  // world positions
  const std::vector<Triangle>* triangles = nullptr;
  glm::dvec3 origin{0.0};

  struct Corners {
    glm::dvec3 a, b, c;
  };
  Corners corners(std::uint32_t triangle) const {
    const auto& v = (*triangles)[triangle].vertex;
    return {(*vertices)[v[0]] - origin, (*vertices)[v[1]] - origin, (*vertices)[v[2]] - origin};
  }
  std::uint32_t size() const { return triangles ? static_cast<std::uint32_t>(triangles->size()) : 0; }
};

void triangleBounds(const RTCBoundsFunctionArguments* args) {
  const auto& data = *static_cast<const TriangleData*>(args->geometryUserPtr);
  const TriangleData::Corners t = data.corners(args->primID);
  glm::vec3 lower(INFINITY), upper(-INFINITY);
  for (const glm::dvec3* corner : {&t.a, &t.b, &t.c}) {
    lower = glm::min(lower, glm::vec3(*corner));
    upper = glm::max(upper, glm::vec3(*corner));
  }
  // Embree's traversal of user geometry is not conservative at box corners; a margin keeps every ray
  // through a vertex.
  const float margin = 0x1p-20f * std::max({std::fabs(lower.x), std::fabs(lower.y), std::fabs(lower.z),
                                           std::fabs(upper.x), std::fabs(upper.y), std::fabs(upper.z)});
  lower -= margin;
  upper += margin;
  *args->bounds_o = RTCBounds{lower.x, lower.y, lower.z, 0.0f, upper.x, upper.y, upper.z, 0.0f};
}

template <typename Args>
bool testTriangle(const Args* args, TriangleHit& hit) {
  const auto* query = reinterpret_cast<const QueryContext*>(args->context);
  if (args->primID == query->ray->excludedTriangle) return false;
  const auto& data = *static_cast<const TriangleData*>(args->geometryUserPtr);
  const TriangleData::Corners t = data.corners(args->primID);
  return intersectWatertight(query->prepared, t.a, t.b, t.c, query->ray->tNear, query->tFar, hit);
}

void intersectTriangle(const RTCIntersectFunctionNArguments* args) {
  if (!args->valid[0]) return;
  auto* query = reinterpret_cast<QueryContext*>(args->context);
  TriangleHit hit;
  if (!testTriangle(args, hit)) return;
  if (query->triangle != RTC_INVALID_GEOMETRY_ID &&
      !replacesClosestHit(hit.t, args->primID, query->hit.t, query->triangle))
    return;
  query->hit = hit;
  query->triangle = args->primID;
  query->tFar = std::min(query->ray->tFar, tieSearchLimit(hit.t));
  // Embree culls by the float tfar: round up, so a triangle tied with this one is still visited.
  auto* rayHit = reinterpret_cast<RTCRayHit*>(args->rayhit);
  rayHit->ray.tfar = nextFloatUp(static_cast<float>(query->tFar));
  rayHit->hit.primID = args->primID;
  rayHit->hit.geomID = args->geomID;
}

void occludeTriangle(const RTCOccludedFunctionNArguments* args) {
  if (!args->valid[0]) return;
  TriangleHit hit;
  if (testTriangle(args, hit)) reinterpret_cast<RTCRay*>(args->ray)->tfar = -INFINITY;
}

class EmbreeAccel final : public Accel {
 public:
  EmbreeAccel(const SceneGeometry& scene, const glm::dvec3& origin, BuildProgress progress, void* progressUser)
      : Accel(origin) {
    RTCDevice device = sharedDevice();
    scene_ = rtcNewScene(device);
    // ROBUST: watertight triangle tests (SPEC section 6). MEDIUM build quality: the viewer must show
    // a freshly loaded 1M-triangle scene quickly; HIGH builds take several times longer for ~10 % faster rays.
    // COMPACT from kCompactBvhTriangles up: a smaller BVH (about 25 B per triangle less, and a lower peak while
    // building) for ~3 % slower rays; below, where memory is not what limits, the faster layout.
    rtcSetSceneFlags(scene_, scene.triangles.size() >= kCompactBvhTriangles
                                 ? RTC_SCENE_FLAG_ROBUST | RTC_SCENE_FLAG_COMPACT
                                 : RTC_SCENE_FLAG_ROBUST);
    rtcSetSceneBuildQuality(scene_, RTC_BUILD_QUALITY_MEDIUM);
    ProgressRelay relay{progress, progressUser};
    if (progress) rtcSetSceneProgressMonitorFunction(scene_, relayProgress, &relay);

    data_ = {&scene.vertices, &scene.triangles, origin};
    if (!scene.triangles.empty()) {
      RTCGeometry geometry = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_USER);
      rtcSetGeometryUserPrimitiveCount(geometry, static_cast<unsigned>(scene.triangles.size()));
      rtcSetGeometryUserData(geometry, &data_);
      rtcSetGeometryBoundsFunction(geometry, triangleBounds, nullptr);
      rtcSetGeometryIntersectFunction(geometry, intersectTriangle);
      rtcSetGeometryOccludedFunction(geometry, occludeTriangle);
      rtcCommitGeometry(geometry);
      rtcAttachGeometry(scene_, geometry);
      rtcReleaseGeometry(geometry);
    }
    rtcCommitScene(scene_);
    if (progress) rtcSetSceneProgressMonitorFunction(scene_, nullptr, nullptr);
    if (rtcGetDeviceError(device) != RTC_ERROR_NONE) {
      rtcReleaseScene(scene_);
      scene_ = nullptr;
    }
  }

  ~EmbreeAccel() override {
    if (scene_) rtcReleaseScene(scene_);
  }

  bool valid() const { return scene_ != nullptr; }

  std::optional<Hit> closestHit(const Ray& ray) const override {
    if (!representable(ray)) return closestHitWithoutEmbree(ray);
    QueryContext query;
    initContext(query, ray);
    RTCRayHit rayHit;
    fill(rayHit.ray, ray);
    rayHit.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rayHit.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(scene_, &query.context, &rayHit);
    if (query.triangle == RTC_INVALID_GEOMETRY_ID) return std::nullopt;
    return Hit{query.hit.t, query.triangle, query.hit.b1, query.hit.b2};
  }

  bool occluded(const Ray& ray) const override {
    if (!representable(ray)) return occludedWithoutEmbree(ray);
    QueryContext query;
    initContext(query, ray);
    RTCRay r;
    fill(r, ray);
    rtcOccluded1(scene_, &query.context, &r);
    return r.tfar < 0.0f;  // Embree sets tfar to -inf on a hit
  }

  AccelKind kind() const override { return AccelKind::Embree; }

 private:
  // buildAccel() only builds this back-end for scenes whose rays stay within kEmbreeCoordinateLimit, but a
  // caller may still trace a ray from elsewhere (the viewer's camera moved far from the build origin).
  // Embree asserts on such a ray: it is answered here by testing every triangle, in double.
  static bool representable(const Ray& ray) {
    const double limit = kEmbreeCoordinateLimit;
    for (int k = 0; k < 3; ++k)
      if (!(std::fabs(ray.origin[k]) <= limit) || !(std::fabs(ray.direction[k]) <= limit)) return false;
    return ray.tNear >= 0.0 && !std::isnan(ray.tFar);
  }

  std::optional<Hit> closestHitWithoutEmbree(const Ray& ray) const {
    const WatertightRay prepared = prepareWatertightRay(ray.origin, ray.direction);
    std::optional<Hit> best;
    for (std::uint32_t i = 0; i < data_.size(); ++i) {
      if (i == ray.excludedTriangle) continue;
      const TriangleData::Corners t = data_.corners(i);
      TriangleHit hit;
      const double tFar = best ? std::min(ray.tFar, tieSearchLimit(best->t)) : ray.tFar;
      if (!intersectWatertight(prepared, t.a, t.b, t.c, ray.tNear, tFar, hit)) continue;
      if (best && !replacesClosestHit(hit.t, i, best->t, best->triangle)) continue;
      best = Hit{hit.t, i, hit.b1, hit.b2};
    }
    return best;
  }

  bool occludedWithoutEmbree(const Ray& ray) const {
    const WatertightRay prepared = prepareWatertightRay(ray.origin, ray.direction);
    for (std::uint32_t i = 0; i < data_.size(); ++i) {
      if (i == ray.excludedTriangle) continue;
      const TriangleData::Corners t = data_.corners(i);
      TriangleHit hit;
      if (intersectWatertight(prepared, t.a, t.b, t.c, ray.tNear, ray.tFar, hit)) return true;
    }
    return false;
  }

  // The float copy Embree traverses its boxes with; the interval rounded outward.
  static void fill(RTCRay& out, const Ray& ray) {
    out.org_x = static_cast<float>(ray.origin.x);
    out.org_y = static_cast<float>(ray.origin.y);
    out.org_z = static_cast<float>(ray.origin.z);
    out.dir_x = static_cast<float>(ray.direction.x);
    out.dir_y = static_cast<float>(ray.direction.y);
    out.dir_z = static_cast<float>(ray.direction.z);
    out.tnear = std::max(0.0f, nextFloatDown(static_cast<float>(ray.tNear)));
    out.tfar = nextFloatUp(static_cast<float>(ray.tFar));
    out.time = 0.0f;
    out.mask = std::numeric_limits<unsigned>::max();
    out.id = 0;
    out.flags = 0;
  }

  RTCScene scene_ = nullptr;
  TriangleData data_;
};

}  // namespace

std::unique_ptr<Accel> makeEmbreeAccel(const SceneGeometry& scene, const glm::dvec3& origin, BuildProgress progress,
                                       void* progressUser) {
  auto accel = std::make_unique<EmbreeAccel>(scene, origin, progress, progressUser);
  if (!accel->valid()) return nullptr;  // cancelled through the progress callback
  return accel;
}

}  // namespace rayview
