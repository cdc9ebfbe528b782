// Embree 3 back-end: one triangle geometry holding every scene triangle, in float, relative to origin(). Embree's
// functions come from the library loaded when first needed (embree_library.h).
#include <embree3/rtcore.h>

#include <cstdio>
#include <cstring>
#include <limits>
#include <map>
#include <mutex>
#include <stdexcept>
#include <string>

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include <glm/common.hpp>

#include "accel_backends.h"
#include "rayview/cut_outs.h"
#include "embree_library.h"
#include "float_rays.h"
#include "float_steps.h"
#include "isa_clones.h"
#include "watertight_lanes.h"
#include "watertight_triangle.h"

namespace rayview {
namespace {

// Loaded before any back-end is made (buildCheckedAccel, makeEmbreeAccelForIsa check it).
const EmbreeLibrary& embree() { return *embreeLibrary(); }

void reportDeviceError(void*, RTCError code, const char* message) {
  if (code == RTC_ERROR_CANCELLED) return;  // a build we cancelled on purpose
  std::fprintf(stderr, "rayview: Embree error %d: %s\n", static_cast<int>(code), message ? message : "");
}

RTCDevice newDevice(const char* config) {
  RTCDevice d = embree().NewDevice(config);
  if (!d) throw std::runtime_error("Embree: cannot create a device");
  embree().SetDeviceErrorFunction(d, reportDeviceError, nullptr);
  return d;
}

// One device per layout and process, made when first needed: creating a device is not free. How many user
// primitives a leaf may hold is a device setting (Embree's default is one); the compact layout's device allows two.
RTCDevice sharedDevice(EmbreeLayout layout) {
  if (layout == EmbreeLayout::Compact || layout == EmbreeLayout::CompactQuick) {
    static RTCDevice compact = newDevice("object_accel_max_leaf_size=2");
    return compact;
  }
  static RTCDevice fast = newDevice(nullptr);
  return fast;
}

// A device limited to one vector ISA, one per ISA and process, for tests (makeEmbreeAccelForIsa).
RTCDevice isaDevice(const std::string& isa) {
  static std::mutex mutex;
  static std::map<std::string, RTCDevice> devices;
  const std::lock_guard<std::mutex> lock(mutex);
  RTCDevice& device = devices[isa];
  if (!device) device = newDevice(("isa=" + isa).c_str());
  return device;
}

struct ProgressRelay {
  BuildProgress callback;
  void* user;
};

// The ray in double travels with the query: Embree traverses its float boxes with a float copy, and
// every candidate triangle is tested against the double ray. The closest hit so far is kept here too (the
// interval's end it implies in QueryContext::tFar).
struct QueryLane {
  const Ray* ray = nullptr;
  WatertightRay prepared;  // a single ray's; a packet's lanes are prepared in QueryContext::packed
  TriangleHit hit;
  unsigned triangle = RTC_INVALID_GEOMETRY_ID;
};

// One lane per ray of the query (1, or up to kRayPacket for a packet). Each float ray's `id` is its lane: the
// callbacks find their double ray by it, whatever packet size and order Embree calls them with.
struct QueryContext {
  RTCIntersectContext context;  // first member: Embree hands back a pointer to it
  QueryLane* lanes;
  // Each lane's end of the interval still searched: the ray's tFar, then the closest hit so far plus the tie band.
  // For a packet, packed->tFar; for a single ray, a double of the query's own.
  double* tFar;
  // A packet query's rays again, as the four-wide test reads them (watertight_lanes.h). Null for a single ray.
  WatertightLanes<kRayPacket>* packed = nullptr;
};

void initLane(QueryLane& lane, const Ray& ray) {
  lane.ray = &ray;
  lane.prepared = prepareWatertightRay(ray.origin, ray.direction);
  lane.triangle = RTC_INVALID_GEOMETRY_ID;
}

bool relayProgress(void* ptr, double fraction) {
  auto* relay = static_cast<ProgressRelay*>(ptr);
  return relay->callback(relay->user, fraction);
}

// Triangles as user primitives: Embree's BVH and traversal, the watertight test of watertight_triangle.h
// in double on the camera-relative double vertices (Embree 3's own robust test misses some rays through
// shared vertices; see docs/numerics.md).
// The scene's own arrays, borrowed (the scene outlives the accel: buildAccel's contract): no copy of the vertices or
// the indices, 24-84 B per triangle less (docs/PERFORMANCE.md, "Memory per triangle"). A triangle's corners relative to
// the origin are computed per test, in double, exactly as a stored relative copy held them.
struct TriangleData {
  const SceneArray<glm::dvec3>* vertices = nullptr;  // world positions
  const SceneArray<Triangle>* triangles = nullptr;
  glm::dvec3 origin{0.0};
  const CutOuts* cutOuts = nullptr;  // null for a scene without cut-outs

  TriangleCorners corners(std::uint32_t triangle) const { return cornersOf(*vertices, (*triangles)[triangle], origin); }
  std::uint32_t size() const { return triangles ? static_cast<std::uint32_t>(triangles->size()) : 0; }
};

void triangleBounds(const RTCBoundsFunctionArguments* args) {
  const auto& data = *static_cast<const TriangleData*>(args->geometryUserPtr);
  const FloatBox box = floatBoxOf(data.corners(args->primID));
  *args->bounds_o =
      RTCBounds{box.lower.x, box.lower.y, box.lower.z, 0.0f, box.upper.x, box.upper.y, box.upper.z, 0.0f};
}

// Whether a hit of the triangle counts: not where a cut-out hides it. The callbacks come in two builds, with and
// without cut-outs (kCutOuts), registered by the scene's: with a run-time test of a null pointer instead, car's
// render took 0.9 % more instructions (callgrind) for scenes without any.
template <bool kCutOuts>
bool kept([[maybe_unused]] const CutOuts* cutOuts, [[maybe_unused]] unsigned primID,
          [[maybe_unused]] const TriangleHit& hit) {
  if constexpr (kCutOuts)
    return !cutOuts->hides(primID, hit.b1, hit.b2);
  else
    return true;
}

// Query lane `id` against the triangle, by the scalar test.
bool testTriangle(const TriangleCorners& t, unsigned primID, const QueryContext& query, unsigned id,
                  TriangleHit& hit) {
  const QueryLane& lane = query.lanes[id];
  if (primID == lane.ray->excludedTriangle) return false;
  if (query.packed) return intersectWatertight(query.packed->ray(id), t.a, t.b, t.c, lane.ray->tNear, query.tFar[id], hit);
  return intersectWatertight(lane.prepared, t.a, t.b, t.c, lane.ray->tNear, query.tFar[id], hit);
}

// The valid lanes of a callback's N, each tested against the triangle; `onHit(i, id, hit)` gets each valid lane i
// (query lane `id`, the float ray's id) whose ray hits it, does not exclude it and is not in a cut-out (`cutOuts`,
// null for none), in increasing order of i, as a plain loop over the lanes gives them. For a packet query (`packed`
// set), four consecutive lanes of Embree's that are four consecutive query lanes from a multiple of four (Embree
// hands a 16-wide packet whole on an AVX-512 machine, in halves or quarters on others: all line up), two or more of
// them valid and sharing their axis permutation, go through the four-wide test; every other lane through the scalar
// one.
template <bool kCutOuts, class OnHit>
void testLanes(const QueryContext& query, const int* valid, unsigned N, RTCRayN* rays, const TriangleCorners& t,
               unsigned primID, const CutOuts* cutOuts, OnHit&& onHit) {
  const WatertightLanes<kRayPacket>* packed = query.packed;
  const QueryLane* lanes = query.lanes;
  auto id = [&](unsigned i) { return RTCRayN_id(rays, N, i); };
  unsigned first = 0;
  for (; packed && first + kWatertightWidth <= N; first += kWatertightWidth) {
    unsigned block = 0;
    for (int j = 0; j < kWatertightWidth; ++j)
      if (valid[first + j] && lanes[id(first + j)].ray) block |= 1u << j;
    if (block == 0) continue;
    const unsigned lane0 = id(first);
    bool vector = (block & (block - 1)) != 0 && lane0 % kWatertightWidth == 0 && lane0 < kRayPacket;
    for (int j = 1; j < kWatertightWidth && vector; ++j) vector = id(first + j) == lane0 + j;
    int permutation = -1;
    for (int j = 0; j < kWatertightWidth && vector; ++j) {
      if (!(block & (1u << j))) continue;
      if (permutation < 0) permutation = packed->permutation[lane0 + j];
      vector = packed->permutation[lane0 + j] == permutation;
    }
    if (vector) {
      TriangleHits4 hits;
      const unsigned hit =
          block & intersectWatertight4(*packed, static_cast<int>(lane0), permutation, t.a, t.b, t.c, hits);
      for (unsigned j = 0; j < kWatertightWidth; ++j)
        if ((hit & (1u << j)) && primID != lanes[lane0 + j].ray->excludedTriangle &&
            kept<kCutOuts>(cutOuts, primID, hits[j]))
          onHit(first + j, lane0 + j, hits[j]);
      continue;
    }
    for (unsigned j = 0; j < kWatertightWidth; ++j) {
      if (!(block & (1u << j))) continue;
      TriangleHit one;
      if (testTriangle(t, primID, query, id(first + j), one) && kept<kCutOuts>(cutOuts, primID, one))
        onHit(first + j, id(first + j), one);
    }
  }
  for (unsigned i = first; i < N; ++i) {
    if (!valid[i] || !lanes[id(i)].ray) continue;
    TriangleHit one;
    if (testTriangle(t, primID, query, id(i), one) && kept<kCutOuts>(cutOuts, primID, one)) onHit(i, id(i), one);
  }
}

template <bool kCutOuts>
RAYVIEW_HOT void intersectTriangle(const RTCIntersectFunctionNArguments* args) {
  const auto& data = *static_cast<const TriangleData*>(args->geometryUserPtr);
  const QueryContext& query = *reinterpret_cast<QueryContext*>(args->context);
  QueryLane* lanes = query.lanes;
  RTCRayN* rays = RTCRayHitN_RayN(args->rayhit, args->N);
  RTCHitN* hits = RTCRayHitN_HitN(args->rayhit, args->N);
  const TriangleCorners corners = data.corners(args->primID);  // once for every lane
  // Lane i of Embree's arguments (lane `id` of the query) hits at `hit`: the closest so far?
  testLanes<kCutOuts>(query, args->valid, args->N, rays, corners, args->primID, data.cutOuts,
            [&](unsigned i, unsigned id, const TriangleHit& hit) {
              QueryLane& lane = lanes[id];
              if (lane.triangle != RTC_INVALID_GEOMETRY_ID &&
                  !replacesClosestHit(hit.t, args->primID, lane.hit.t, lane.triangle))
                return;
              lane.hit = hit;
              lane.triangle = args->primID;
              query.tFar[id] = std::min(lane.ray->tFar, tieSearchLimit(hit.t));
              // Embree culls by the float tfar: widened, so a triangle tied with this one is still visited.
              RTCRayN_tfar(rays, args->N, i) = widenedFar(query.tFar[id]);
              RTCHitN_primID(hits, args->N, i) = args->primID;
              RTCHitN_geomID(hits, args->N, i) = args->geomID;
            });
}

template <bool kCutOuts>
RAYVIEW_HOT void occludeTriangle(const RTCOccludedFunctionNArguments* args) {
  const auto& data = *static_cast<const TriangleData*>(args->geometryUserPtr);
  const QueryContext& query = *reinterpret_cast<QueryContext*>(args->context);
  testLanes<kCutOuts>(query, args->valid, args->N, args->ray, data.corners(args->primID), args->primID, data.cutOuts,
                      [&](unsigned i, unsigned, const TriangleHit&) {
                        RTCRayN_tfar(args->ray, args->N, i) = -INFINITY;
                      });
}

// A packet query's lanes and Embree's packet, kept per thread: set up on the stack they cost ~3 KB of
// zeroing per packet, a packet of shadow rays often holding only a few (callgrind: ~8 % of car's instructions).
// Lanes beyond a query's count get an empty interval (fillPacket): with an earlier query's rays left in them,
// Embree's packet traversal did ~3 % more work.
struct PacketScratch {
  QueryLane lanes[kRayPacket];
  WatertightLanes<kRayPacket> packed;
  alignas(64) RTCRayHit16 rayHit{};
  alignas(64) RTCRay16 ray{};
  alignas(64) int valid[kRayPacket] = {};

  // What every query's float rays share (Embree never writes these): set once.
  PacketScratch() {
    for (RTCRay16* packet : {&rayHit.ray, &ray})
      for (int k = 0; k < kRayPacket; ++k) {
        packet->time[k] = 0.0f;
        packet->mask[k] = std::numeric_limits<unsigned>::max();
        packet->id[k] = static_cast<unsigned>(k);  // its lane
        packet->flags[k] = 0;
      }
  }
};

PacketScratch& packetScratch() {
  thread_local PacketScratch scratch;  // closestHits and occludedMany never nest on a thread
  return scratch;
}

class EmbreeAccel final : public Accel {
 public:
  EmbreeAccel(const SceneGeometry& scene, const glm::dvec3& origin, RTCDevice device, EmbreeLayout layout,
              BuildProgress progress, void* progressUser, const CutOuts* cutOuts)
      : Accel(origin, scene), rtc_(embree()) {
    scene_ = rtc_.NewScene(device);
    // ROBUST: watertight triangle tests (SPEC section 6). MEDIUM build quality: the viewer must show
    // a freshly loaded 1M-triangle scene quickly; HIGH builds take several times longer for ~10 % faster rays.
    // The compact layout (embreeLayoutFor) adds COMPACT: a smaller BVH for ~3 % slower rays.
    const bool compact = layout == EmbreeLayout::Compact || layout == EmbreeLayout::CompactQuick;
    const bool quick = layout == EmbreeLayout::Quick || layout == EmbreeLayout::CompactQuick;
    rtc_.SetSceneFlags(scene_, compact ? RTC_SCENE_FLAG_ROBUST | RTC_SCENE_FLAG_COMPACT : RTC_SCENE_FLAG_ROBUST);
    rtc_.SetSceneBuildQuality(scene_, quick ? RTC_BUILD_QUALITY_LOW : RTC_BUILD_QUALITY_MEDIUM);
    ProgressRelay relay{progress, progressUser};
    if (progress) rtc_.SetSceneProgressMonitorFunction(scene_, relayProgress, &relay);

    data_ = {&scene.vertices, &scene.triangles, origin, cutOuts};
    if (!scene.triangles.empty()) {
      RTCGeometry geometry = rtc_.NewGeometry(device, RTC_GEOMETRY_TYPE_USER);
      rtc_.SetGeometryUserPrimitiveCount(geometry, static_cast<unsigned>(scene.triangles.size()));
      rtc_.SetGeometryUserData(geometry, &data_);
      rtc_.SetGeometryBoundsFunction(geometry, triangleBounds, nullptr);
      rtc_.SetGeometryIntersectFunction(geometry, cutOuts ? intersectTriangle<true> : intersectTriangle<false>);
      rtc_.SetGeometryOccludedFunction(geometry, cutOuts ? occludeTriangle<true> : occludeTriangle<false>);
      rtc_.CommitGeometry(geometry);
      rtc_.AttachGeometry(scene_, geometry);
      rtc_.ReleaseGeometry(geometry);
    }
    rtc_.CommitScene(scene_);
    if (progress) rtc_.SetSceneProgressMonitorFunction(scene_, nullptr, nullptr);
    if (rtc_.GetDeviceError(device) != RTC_ERROR_NONE) {
      rtc_.ReleaseScene(scene_);
      scene_ = nullptr;
    }
  }

  ~EmbreeAccel() override {
    if (scene_) rtc_.ReleaseScene(scene_);
  }

  bool valid() const { return scene_ != nullptr; }

  std::optional<Hit> closestHit(const Ray& ray) const override {
    if (!floatTraversable(ray)) return closestHitWithoutEmbree(ray);
    QueryLane lane;
    initLane(lane, ray);
    double tFar = ray.tFar;
    QueryContext query{{}, &lane, &tFar};
    rtcInitIntersectContext(&query.context);
    RTCRayHit rayHit;
    fill(rayHit.ray, ray);
    rayHit.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rayHit.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtc_.Intersect1(scene_, &query.context, &rayHit);
    return hitOf(lane);
  }

  void closestHits(const Ray* rays, int count, std::optional<Hit>* hits) const override {
    PacketScratch& scratch = packetScratch();
    QueryLane* lanes = scratch.lanes;
    RTCRayHit16& packet = scratch.rayHit;
    int* valid = scratch.valid;
    if (!fillPacket(rays, count, lanes, scratch.packed, packet.ray, valid,
                    [&](int k) { hits[k] = closestHitWithoutEmbree(rays[k]); }))
      return;
    for (int k = 0; k < kRayPacket; ++k) {
      packet.hit.geomID[k] = RTC_INVALID_GEOMETRY_ID;
      packet.hit.instID[0][k] = RTC_INVALID_GEOMETRY_ID;
    }
    QueryContext query{{}, lanes, scratch.packed.tFar, &scratch.packed};
    rtcInitIntersectContext(&query.context);
    query.context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
    rtc_.Intersect16(valid, scene_, &query.context, &packet);
    // Each hit constructed in place: assigned from a returned optional, it went through the stack and its wide
    // loads of narrow stores missed store forwarding.
    for (int k = 0; k < count; ++k) {
      if (!valid[k]) continue;
      const QueryLane& lane = lanes[k];
      if (lane.triangle == RTC_INVALID_GEOMETRY_ID) {
        hits[k].reset();
        continue;
      }
      Hit& hit = hits[k].emplace();
      hit.t = lane.hit.t;
      hit.triangle = lane.triangle;
      hit.b1 = lane.hit.b1;
      hit.b2 = lane.hit.b2;
    }
  }

  void occludedMany(const Ray* rays, int count, bool* answers) const override {
    PacketScratch& scratch = packetScratch();
    QueryLane* lanes = scratch.lanes;
    RTCRay16& packet = scratch.ray;
    int* valid = scratch.valid;
    if (!fillPacket(rays, count, lanes, scratch.packed, packet, valid,
                    [&](int k) { answers[k] = occludedWithoutEmbree(rays[k]); }))
      return;
    QueryContext query{{}, lanes, scratch.packed.tFar, &scratch.packed};
    rtcInitIntersectContext(&query.context);
    query.context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
    rtc_.Occluded16(valid, scene_, &query.context, &packet);
    for (int k = 0; k < count; ++k)
      if (valid[k]) answers[k] = packet.tfar[k] < 0.0f;  // Embree sets tfar to -inf on a hit
  }

  bool occluded(const Ray& ray) const override {
    if (!floatTraversable(ray)) return occludedWithoutEmbree(ray);
    QueryLane lane;
    initLane(lane, ray);
    double tFar = ray.tFar;
    QueryContext query{{}, &lane, &tFar};
    rtcInitIntersectContext(&query.context);
    RTCRay r;
    fill(r, ray);
    rtc_.Occluded1(scene_, &query.context, &r);
    return r.tfar < 0.0f;  // Embree sets tfar to -inf on a hit
  }

  AccelKind kind() const override { return AccelKind::Embree; }

 private:
  static std::optional<Hit> hitOf(const QueryLane& lane) {
    if (lane.triangle == RTC_INVALID_GEOMETRY_ID) return std::nullopt;
    return Hit{lane.hit.t, lane.triangle, lane.hit.b1, lane.hit.b2};
  }

  // buildAccel() only builds this back-end for scenes whose rays stay within kEmbreeCoordinateLimit, but a
  // caller may still trace a ray from elsewhere (the viewer's camera moved far from the build origin).
  // Embree asserts on such a ray: floatTraversable() turns it away, and it is answered here by testing every
  // triangle, in double.
  std::optional<Hit> closestHitWithoutEmbree(const Ray& ray) const {
    return closestHitByEveryTriangle(ray, data_.size(), data_.cutOuts,
                                     [&](std::uint32_t i) { return data_.corners(i); });
  }

  bool occludedWithoutEmbree(const Ray& ray) const {
    return occludedByAnyTriangle(ray, data_.size(), data_.cutOuts, [&](std::uint32_t i) { return data_.corners(i); });
  }

  // A lane the query does not use. Its valid entry is 0, but Embree's AVX2 packet traversal hands the callbacks
  // lanes that its valid mask left out whenever their interval is not empty (a [0, 0] one included): so the interval
  // is empty, and the callbacks skip a lane without a ray (testLanes) rather than read a ray an earlier query left.
  static void leaveOut(RTCRay16& packet, QueryLane* lanes, int k) {
    packet.tfar[k] = -INFINITY;
    lanes[k].ray = nullptr;
  }

  // Lanes k < count of a packet, each ray's float copy with its lane as id; a ray Embree cannot take is answered
  // by `without(k)` and left out (valid[k] = 0). Returns whether any lane is left for Embree.
  // Four rays at a time in vector registers (one at a time it was ~10 % of a render): each lane gets exactly what
  // floatTraversable(), prepareWatertightRay() and fill() give its ray alone (WatertightLanes.PreparedFourAtOnceAsOneAtATime,
  // FloatSteps.FourWideAgreeWithTheScalarSteps, and Packets.AnswerEachRayAsItsOwnQueryDoes for the whole query).
  // Lanes from `count` on are left out as well.
  template <class Without>
  RAYVIEW_HOT static bool fillPacket(const Ray* rays, int count, QueryLane* lanes,
                                     WatertightLanes<kRayPacket>& packed, RTCRay16& packet, int* valid,
                                     Without&& without) {
    bool any = false;
    int first = 0;
    for (; first < count; first += kWatertightWidth) {
      const FloatRays4 f = prepareFourRays(rays, first, count, packed);
      const Int4 usable = f.usable, inCount = f.inCount;
      // A lane Embree does not take gets zeros.
      auto put = [&](float* to, Float4 v) { std::memcpy(to + first, &v, sizeof v); };
      put(packet.org_x, f.origin[0]);
      put(packet.org_y, f.origin[1]);
      put(packet.org_z, f.origin[2]);
      put(packet.dir_x, f.direction[0]);
      put(packet.dir_y, f.direction[1]);
      put(packet.dir_z, f.direction[2]);
      put(packet.tnear, f.tNear);
      put(packet.tfar, f.tFar);
      for (int j = 0; j < kWatertightWidth; ++j) {
        const int k = first + j;
        valid[k] = usable[j];
        if (usable[j]) {
          lanes[k].ray = &rays[k];
          lanes[k].triangle = RTC_INVALID_GEOMETRY_ID;
          any = true;
        } else {
          leaveOut(packet, lanes, k);
          if (inCount[j]) without(k);
        }
      }
    }
    for (; first < kRayPacket; first += kWatertightWidth) {
      for (float* field : {packet.org_x, packet.org_y, packet.org_z, packet.dir_x, packet.dir_y, packet.dir_z,
                           packet.tnear})
        std::memset(field + first, 0, kWatertightWidth * sizeof(float));
      for (int j = 0; j < kWatertightWidth; ++j) {
        valid[first + j] = 0;
        leaveOut(packet, lanes, first + j);
      }
    }
    return any;
  }

  // The float copy Embree traverses its boxes with; the interval rounded outward.
  static void fill(RTCRay& out, const Ray& ray) {
    const FloatRay f = floatRay(ray);
    out.org_x = f.origin[0];
    out.org_y = f.origin[1];
    out.org_z = f.origin[2];
    out.dir_x = f.direction[0];
    out.dir_y = f.direction[1];
    out.dir_z = f.direction[2];
    out.tnear = f.tNear;
    out.tfar = f.tFar;
    out.time = 0.0f;
    out.mask = std::numeric_limits<unsigned>::max();
    out.id = 0;
    out.flags = 0;
  }

  const EmbreeLibrary& rtc_;  // the loaded library's functions, read on every query
  RTCScene scene_ = nullptr;
  TriangleData data_;
};

}  // namespace

EmbreeLayout embreeLayoutFor(std::size_t triangles, std::size_t pixels) {
  const bool fewRays = pixels > 0 && pixels < kQuickBuildRaysPerTriangle * triangles;
  if (triangles >= kCompactBvhTriangles) return fewRays ? EmbreeLayout::CompactQuick : EmbreeLayout::Compact;
  return fewRays ? EmbreeLayout::Quick : EmbreeLayout::Fast;
}

std::unique_ptr<Accel> makeEmbreeAccel(const SceneGeometry& scene, const glm::dvec3& origin, EmbreeLayout layout,
                                       BuildProgress progress, void* progressUser, const CutOuts* cutOuts) {
  auto accel =
      std::make_unique<EmbreeAccel>(scene, origin, sharedDevice(layout), layout, progress, progressUser, cutOuts);
  if (!accel->valid()) return nullptr;  // cancelled through the progress callback
  return accel;
}

std::unique_ptr<Accel> makeEmbreeAccelForIsa(const SceneGeometry& scene, const glm::dvec3& origin,
                                             const std::string& isa, const CutOuts* cutOuts) {
  std::string why;
  if (!embreeLibrary(&why)) throw std::runtime_error("Embree: " + why);
  auto accel =
      std::make_unique<EmbreeAccel>(scene, origin, isaDevice(isa), EmbreeLayout::Fast, nullptr, nullptr, cutOuts);
  if (!accel->valid()) return nullptr;
  return accel;
}

}  // namespace rayview
