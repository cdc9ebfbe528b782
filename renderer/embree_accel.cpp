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

// An intersect context that remembers one triangle to ignore (the one a secondary ray leaves).
struct ExcludingContext {
  RTCIntersectContext context;  // first member: Embree hands back a pointer to it
  unsigned excludedTriangle;
};

void skipExcludedTriangle(const RTCFilterFunctionNArguments* args) {
  const auto* self = reinterpret_cast<const ExcludingContext*>(args->context);
  for (unsigned i = 0; i < args->N; ++i)
    if (args->valid[i] != 0 && RTCHitN_primID(args->hit, args->N, i) == self->excludedTriangle) args->valid[i] = 0;
}

void initContext(ExcludingContext& c, std::uint32_t excludedTriangle) {
  rtcInitIntersectContext(&c.context);
  c.excludedTriangle = excludedTriangle;
  if (excludedTriangle != kNoTriangle) c.context.filter = skipExcludedTriangle;
}

bool relayProgress(void* ptr, double fraction) {
  auto* relay = static_cast<ProgressRelay*>(ptr);
  return relay->callback(relay->user, fraction);
}

// Triangles as user primitives: Embree's BVH and traversal, the watertight test of watertight_triangle.h
// in double on the camera-relative double vertices (Embree 3's own robust test misses some rays through
// shared vertices; see docs/numerics.md).
struct TriangleData {
  std::vector<glm::dvec3> vertices;  // relative to the origin, in double
  std::vector<std::array<std::uint32_t, 3>> triangles;
};

void triangleBounds(const RTCBoundsFunctionArguments* args) {
  const auto& data = *static_cast<const TriangleData*>(args->geometryUserPtr);
  const auto& t = data.triangles[args->primID];
  glm::vec3 lower(INFINITY), upper(-INFINITY);
  for (int k = 0; k < 3; ++k) {
    lower = glm::min(lower, glm::vec3(data.vertices[t[k]]));
    upper = glm::max(upper, glm::vec3(data.vertices[t[k]]));
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
bool testTriangle(const Args* args, const RTCRay& ray, TriangleHit& hit) {
  const auto* context = reinterpret_cast<const ExcludingContext*>(args->context);
  if (args->primID == context->excludedTriangle) return false;
  const auto& data = *static_cast<const TriangleData*>(args->geometryUserPtr);
  const auto& t = data.triangles[args->primID];
  const WatertightRay w = prepareWatertightRay(glm::dvec3(ray.org_x, ray.org_y, ray.org_z),
                                               glm::dvec3(ray.dir_x, ray.dir_y, ray.dir_z));
  return intersectWatertight(w, data.vertices[t[0]], data.vertices[t[1]], data.vertices[t[2]], ray.tnear, ray.tfar,
                             hit);
}

void intersectTriangle(const RTCIntersectFunctionNArguments* args) {
  if (!args->valid[0]) return;
  auto* rayHit = reinterpret_cast<RTCRayHit*>(args->rayhit);
  TriangleHit hit;
  if (!testTriangle(args, rayHit->ray, hit)) return;
  rayHit->ray.tfar = static_cast<float>(hit.t);
  rayHit->hit.u = static_cast<float>(hit.b1);
  rayHit->hit.v = static_cast<float>(hit.b2);
  rayHit->hit.primID = args->primID;
  rayHit->hit.geomID = args->geomID;
}

void occludeTriangle(const RTCOccludedFunctionNArguments* args) {
  if (!args->valid[0]) return;
  auto* ray = reinterpret_cast<RTCRay*>(args->ray);
  TriangleHit hit;
  if (testTriangle(args, *ray, hit)) ray->tfar = -INFINITY;
}

class EmbreeAccel final : public Accel {
 public:
  EmbreeAccel(const Scene& scene, const glm::dvec3& origin, BuildProgress progress, void* progressUser)
      : Accel(origin) {
    RTCDevice device = sharedDevice();
    scene_ = rtcNewScene(device);
    // ROBUST: watertight triangle tests (SPEC section 6). MEDIUM build quality: the viewer must show
    // a freshly loaded 1M-triangle scene quickly; HIGH builds take several times longer for ~10 % faster rays.
    // CONTEXT_FILTER_FUNCTION: lets a ray ignore the triangle it leaves (SecondaryRayStart::ExcludeHitTriangle).
    rtcSetSceneFlags(scene_, RTC_SCENE_FLAG_ROBUST | RTC_SCENE_FLAG_CONTEXT_FILTER_FUNCTION);
    rtcSetSceneBuildQuality(scene_, RTC_BUILD_QUALITY_MEDIUM);
    ProgressRelay relay{progress, progressUser};
    if (progress) rtcSetSceneProgressMonitorFunction(scene_, relayProgress, &relay);

    if (!scene.triangles.empty()) {
      data_.vertices.reserve(scene.vertices.size());
      for (const glm::dvec3& v : scene.vertices) data_.vertices.push_back(v - origin);
      data_.triangles.reserve(scene.triangles.size());
      for (const Triangle& t : scene.triangles) data_.triangles.push_back({t.vertex[0], t.vertex[1], t.vertex[2]});
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
    ExcludingContext context;
    initContext(context, ray.excludedTriangle);
    RTCRayHit rayHit;
    fill(rayHit.ray, ray);
    rayHit.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rayHit.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(scene_, &context.context, &rayHit);
    if (rayHit.hit.geomID == RTC_INVALID_GEOMETRY_ID) return std::nullopt;
    return Hit{rayHit.ray.tfar, rayHit.hit.primID, rayHit.hit.u, rayHit.hit.v};
  }

  bool occluded(const Ray& ray) const override {
    ExcludingContext context;
    initContext(context, ray.excludedTriangle);
    RTCRay r;
    fill(r, ray);
    rtcOccluded1(scene_, &context.context, &r);
    return r.tfar < 0.0f;  // Embree sets tfar to -inf on a hit
  }

  AccelKind kind() const override { return AccelKind::Embree; }

 private:
  static void fill(RTCRay& out, const Ray& ray) {
    out.org_x = ray.origin.x;
    out.org_y = ray.origin.y;
    out.org_z = ray.origin.z;
    out.dir_x = ray.direction.x;
    out.dir_y = ray.direction.y;
    out.dir_z = ray.direction.z;
    out.tnear = ray.tNear;
    out.tfar = ray.tFar;
    out.time = 0.0f;
    out.mask = std::numeric_limits<unsigned>::max();
    out.id = 0;
    out.flags = 0;
  }

  RTCScene scene_ = nullptr;
  TriangleData data_;
};

}  // namespace

std::unique_ptr<Accel> makeEmbreeAccel(const Scene& scene, const glm::dvec3& origin, BuildProgress progress,
                                       void* progressUser) {
  auto accel = std::make_unique<EmbreeAccel>(scene, origin, progress, progressUser);
  if (!accel->valid()) return nullptr;  // cancelled through the progress callback
  return accel;
}

}  // namespace rayview
