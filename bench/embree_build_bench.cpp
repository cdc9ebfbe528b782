// What an Embree build of user geometry costs on its own, as rayview builds its BVH (it explained why small scenes got
// rayview's own packet BVH, docs/PERFORMANCE.md): a fresh device, the first build in the process (Embree's and TBB's
// start-up included), then further builds of the same boxes, each timed.
//
//     embree_build_bench [--primitives N] [--builds K] [--quality low|medium|high] [--config DEVICE_CONFIG]
//                        (default: 4968 primitives, bunny's count; 50 builds; medium; Embree's default device)
//
// The primitives are random small boxes in the unit cube. Flags and quality as embree_accel.cpp sets them
// (RTC_SCENE_FLAG_ROBUST, RTC_BUILD_QUALITY_MEDIUM); --quality and --config (rtcNewDevice's string, e.g.
// "threads=1") try other settings.
#include <embree3/rtcore.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <random>
#include <vector>

namespace {

double msSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

struct Boxes {
  std::vector<float> lower;  // x, y, z per primitive
};

void bounds(const RTCBoundsFunctionArguments* args) {
  const auto& boxes = *static_cast<const Boxes*>(args->geometryUserPtr);
  const float* at = &boxes.lower[3 * args->primID];
  *args->bounds_o = RTCBounds{at[0], at[1], at[2], 0.0f, at[0] + 0.01f, at[1] + 0.01f, at[2] + 0.01f, 0.0f};
}

void build(RTCDevice device, const Boxes& boxes, RTCBuildQuality quality) {
  RTCScene scene = rtcNewScene(device);
  rtcSetSceneFlags(scene, RTC_SCENE_FLAG_ROBUST);
  rtcSetSceneBuildQuality(scene, quality);
  RTCGeometry geometry = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_USER);
  rtcSetGeometryUserPrimitiveCount(geometry, static_cast<unsigned>(boxes.lower.size() / 3));
  rtcSetGeometryUserData(geometry, const_cast<Boxes*>(&boxes));
  rtcSetGeometryBoundsFunction(geometry, bounds, nullptr);
  rtcCommitGeometry(geometry);
  rtcAttachGeometry(scene, geometry);
  rtcReleaseGeometry(geometry);
  rtcCommitScene(scene);
  rtcReleaseScene(scene);
}

bool parseQuality(const char* name, RTCBuildQuality& quality) {
  if (std::strcmp(name, "low") == 0) quality = RTC_BUILD_QUALITY_LOW;
  else if (std::strcmp(name, "medium") == 0) quality = RTC_BUILD_QUALITY_MEDIUM;
  else if (std::strcmp(name, "high") == 0) quality = RTC_BUILD_QUALITY_HIGH;
  else return false;
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  int primitives = 4968, builds = 50;
  RTCBuildQuality quality = RTC_BUILD_QUALITY_MEDIUM;
  const char* config = nullptr;
  bool usage = argc % 2 == 0;
  for (int i = 1; i + 1 < argc; i += 2) {
    if (std::strcmp(argv[i], "--primitives") == 0) primitives = std::atoi(argv[i + 1]);
    else if (std::strcmp(argv[i], "--builds") == 0) builds = std::atoi(argv[i + 1]);
    else if (std::strcmp(argv[i], "--config") == 0) config = argv[i + 1];
    else if (std::strcmp(argv[i], "--quality") == 0) usage |= !parseQuality(argv[i + 1], quality);
    else usage = true;
  }
  if (usage || primitives <= 0 || builds <= 0) {
    std::fprintf(stderr, "usage: embree_build_bench [--primitives N] [--builds K] [--quality low|medium|high] "
                         "[--config DEVICE_CONFIG]\n");
    return 2;
  }
  Boxes boxes;
  std::mt19937 random(1);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  boxes.lower.resize(3 * static_cast<std::size_t>(primitives));
  for (float& x : boxes.lower) x = unit(random);

  auto start = std::chrono::steady_clock::now();
  RTCDevice device = rtcNewDevice(config);
  if (!device) {
    std::fprintf(stderr, "embree_build_bench: Embree refused the device configuration\n");
    return 2;
  }
  const double deviceMs = msSince(start);
  start = std::chrono::steady_clock::now();
  build(device, boxes, quality);
  const double firstMs = msSince(start);
  start = std::chrono::steady_clock::now();
  for (int k = 0; k < builds; ++k) build(device, boxes, quality);
  const double eachMs = msSince(start) / builds;
  rtcReleaseDevice(device);
  std::printf("%d user primitives: device %.2f ms, first build %.2f ms, then %.2f ms a build (%.0f ns a primitive)\n",
              primitives, deviceMs, firstMs, eachMs, eachMs * 1e6 / primitives);
  return 0;
}
