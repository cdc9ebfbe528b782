// Embree 3 back-end: one triangle geometry holding every scene triangle, in float, relative to origin().
#include <embree3/rtcore.h>

#include <cstdio>
#include <limits>
#include <mutex>
#include <stdexcept>
#include <string>

#include "accel_backends.h"

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
      RTCGeometry geometry = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
      auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(
          geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), scene.vertices.size()));
      auto* indices = static_cast<unsigned*>(rtcSetNewGeometryBuffer(
          geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), scene.triangles.size()));
      if (!vertices || !indices) throw std::runtime_error("Embree: cannot allocate the geometry buffers");
      for (std::size_t i = 0; i < scene.vertices.size(); ++i) {
        const glm::dvec3 relative = scene.vertices[i] - origin;  // in double, before it becomes float
        vertices[3 * i + 0] = static_cast<float>(relative.x);
        vertices[3 * i + 1] = static_cast<float>(relative.y);
        vertices[3 * i + 2] = static_cast<float>(relative.z);
      }
      for (std::size_t i = 0; i < scene.triangles.size(); ++i)
        for (int k = 0; k < 3; ++k) indices[3 * i + k] = scene.triangles[i].vertex[k];
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
};

}  // namespace

std::unique_ptr<Accel> makeEmbreeAccel(const Scene& scene, const glm::dvec3& origin, BuildProgress progress,
                                       void* progressUser) {
  auto accel = std::make_unique<EmbreeAccel>(scene, origin, progress, progressUser);
  if (!accel->valid()) return nullptr;  // cancelled through the progress callback
  return accel;
}

}  // namespace rayview
