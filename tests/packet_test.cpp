// Packets change how fast answers come, never which: on every conformance scene,
// - Embree's and rayview's packet BVH's 16-wide closestHits / occludedMany give each ray exactly (bit for bit) what
//   closestHit / occluded give it alone, and the packet BVH exactly what Embree gives, for coherent packets (neighbouring camera rays), incoherent ones (random segments), partial
//   packets and packets holding a ray Embree cannot take;
// - Tracer::tracePixels (a block's camera, shadow and mirror rays in packets) gives each pixel exactly the
//   colour and the ray counts of Tracer::tracePixel, on the scene's camera at a reduced resolution.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <optional>
#include <vector>

#include <glm/geometric.hpp>

#include "accel_backends.h"
#include "rayview/accel.h"
#include "rayview/lean_memory.h"
#include "rayview/prepared_scene.h"
#include "rayview/scene_loader.h"
#include "rayview/tracer.h"
#include "support/conformance_scenes.h"
#include "support/scene_builder.h"

namespace rayview {
namespace {

// Deterministic uniform numbers in [0, 1).
struct Random {
  std::uint64_t state;
  double uniform() {
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    return static_cast<double>(state >> 11) * 0x1p-53;
  }
};

bool sameHit(const std::optional<Hit>& a, const std::optional<Hit>& b) {
  if (!a || !b) return !a && !b;
  return a->triangle == b->triangle && std::memcmp(&a->t, &b->t, sizeof a->t) == 0 &&
         std::memcmp(&a->b1, &b->b1, sizeof a->b1) == 0 && std::memcmp(&a->b2, &b->b2, sizeof a->b2) == 0;
}

class Packets : public ::testing::TestWithParam<std::filesystem::path> {};

// 400 packets of rays through the scene, f(rays, count) for each: coherent ones (from the camera toward a 4x4 patch
// of points around a vertex, so that they hit something) and incoherent ones (segments between two random points of
// the scene's box); some partial, some holding a ray beyond what Embree takes or one that excludes a triangle.
template <class F>
void forEachTestPacket(const Scene& scene, const glm::dvec3& origin, F&& f) {
  glm::dvec3 lower(INFINITY), upper(-INFINITY);
  for (const glm::dvec3& v : scene.vertices) {
    lower = glm::min(lower, v - origin);
    upper = glm::max(upper, v - origin);
  }
  if (scene.vertices.empty()) lower = upper = glm::dvec3(0.0);
  Random random{0x9E3779B97F4A7C15ULL};
  auto pointInBox = [&] {
    return lower + glm::dvec3(random.uniform(), random.uniform(), random.uniform()) * (upper - lower);
  };
  for (int p = 0; p < 400; ++p) {
    const int count = p % 7 == 0 ? 1 + p % kRayPacket : kRayPacket;  // some partial packets
    const bool coherent = p % 2 == 0;
    Ray rays[kRayPacket];
    const glm::dvec3 centre =
        scene.vertices.empty()
            ? pointInBox()
            : scene.vertices[static_cast<std::size_t>(random.uniform() * scene.vertices.size())] - origin;
    const glm::dvec3 spread = glm::dvec3(glm::length(centre) * 1e-3);
    for (int k = 0; k < count; ++k) {
      const glm::dvec3 a = coherent ? glm::dvec3(0.0) : pointInBox();
      const glm::dvec3 b = coherent ? centre + glm::dvec3(k % 4, k / 4, 0.5 * (k % 3)) * spread : pointInBox();
      const double length = glm::length(b - a);
      rays[k] = Ray{a, length > 0.0 ? (b - a) / length : glm::dvec3(0, 0, -1), 0.0, coherent ? INFINITY : length};
    }
    if (p % 5 == 1) rays[count / 2].origin.x = 1e30;  // beyond what Embree takes: answered without it
    if (p % 11 == 3) rays[0].excludedTriangle = 0;
    f(rays, count, p);
  }
}

TEST_P(Packets, AnswerEachRayAsItsOwnQueryDoes) {
  const Scene scene = loadSceneFile(GetParam()).scene;
  const glm::dvec3 origin = scene.camera.position;
  for (AccelKind kind : {AccelKind::Embree, AccelKind::Packet}) {
    if (availableAccel(kind) != kind) continue;
    SCOPED_TRACE(std::string(toString(kind)));
    const std::unique_ptr<Accel> accel = buildAccel(scene, kind, origin);
    ASSERT_TRUE(accel);
    int hits = 0, occludedCount = 0, compared = 0;
    forEachTestPacket(scene, origin, [&](const Ray* rays, int count, int p) {
      std::optional<Hit> together[kRayPacket];
      bool blocked[kRayPacket];
      accel->closestHits(rays, count, together);
      accel->occludedMany(rays, count, blocked);
      for (int k = 0; k < count; ++k) {
        const std::optional<Hit> alone = accel->closestHit(rays[k]);
        EXPECT_TRUE(sameHit(together[k], alone)) << "packet " << p << " lane " << k << " of " << count;
        EXPECT_EQ(blocked[k], accel->occluded(rays[k])) << "packet " << p << " lane " << k << " of " << count;
        hits += alone.has_value();
        occludedCount += blocked[k];
        ++compared;
      }
    });
    // The rays must exercise both answers, or the comparison says little.
    if (!scene.triangles.empty()) {
      EXPECT_GT(hits, compared / 10);
      EXPECT_GT(occludedCount, compared / 10);
    }
  }
}

// rayview's packet BVH gives every ray, in a packet or alone, exactly Embree's answer: the same closest triangle,
// distance and barycentrics bit for bit, the same occlusion. (So prepareGeometry may build either for a small scene
// and the image does not change.)
void expectAnswersAsEmbree(const Scene& scene, const glm::dvec3& origin, const Accel& packet) {
  const std::unique_ptr<Accel> embree = buildAccel(scene, AccelKind::Embree, origin);
  ASSERT_TRUE(embree);
  ASSERT_EQ(embree->kind(), AccelKind::Embree);
  ASSERT_EQ(packet.kind(), AccelKind::Packet);
  int hits = 0, compared = 0;
  forEachTestPacket(scene, origin, [&](const Ray* rays, int count, int p) {
    std::optional<Hit> byEmbree[kRayPacket], byPacket[kRayPacket];
    bool blockedByEmbree[kRayPacket], blockedByPacket[kRayPacket];
    embree->closestHits(rays, count, byEmbree);
    packet.closestHits(rays, count, byPacket);
    embree->occludedMany(rays, count, blockedByEmbree);
    packet.occludedMany(rays, count, blockedByPacket);
    for (int k = 0; k < count; ++k) {
      EXPECT_TRUE(sameHit(byPacket[k], byEmbree[k])) << "packet " << p << " lane " << k << " of " << count;
      EXPECT_EQ(blockedByPacket[k], blockedByEmbree[k]) << "packet " << p << " lane " << k << " of " << count;
      hits += byEmbree[k].has_value();
      ++compared;
    }
  });
  if (!scene.triangles.empty()) {
    EXPECT_GT(hits, compared / 10);
  }
}

TEST_P(Packets, PacketBvhAnswersEveryRayAsEmbreeDoes) {
  if (availableAccel(AccelKind::Embree) != AccelKind::Embree) GTEST_SKIP() << "built without Embree";
  const Scene scene = loadSceneFile(GetParam()).scene;
  const std::unique_ptr<Accel> packet = buildAccel(scene, AccelKind::Packet, scene.camera.position);
  ASSERT_TRUE(packet);
  expectAnswersAsEmbree(scene, scene.camera.position, *packet);
}

// The same with leaves of several triangles, as a lean scene's packet BVH is built (rayview/lean_memory.h).
TEST_P(Packets, PacketBvhWithLeanLeavesAnswersEveryRayAsEmbreeDoes) {
  if (availableAccel(AccelKind::Embree) != AccelKind::Embree) GTEST_SKIP() << "built without Embree";
  const Scene scene = loadSceneFile(GetParam()).scene;
  const std::unique_ptr<Accel> packet = makePacketBvhAccel(scene, scene.camera.position, 0, kLeanLeafTriangles);
  ASSERT_TRUE(packet);
  expectAnswersAsEmbree(scene, scene.camera.position, *packet);
}

// Every pixel of a block traced together equals the pixel traced alone (tracePixels against tracePixel, and
// traceSamples against traceSample for one sample of an anti-aliased pixel), colour and ray counts. `single`
// gets the single pixels' ray counts.
void expectBlocksTraceAsSinglePixels(const Scene& scene, int pixelSamples, RayCounts& single,
                                     SecondaryRayStart start = SecondaryRayStart::Offset) {
  const auto geometry = prepareGeometry(scene, AccelKind::Embree, BvhBuild::Interactive);
  RenderSettings settings;
  settings.pixelSamples = pixelSamples;
  settings.secondaryRayStart = start;
  const Tracer tracer(scene, *geometry->accel, geometry->shading, settings);
  ASSERT_EQ(tracer.pixelSamples(), pixelSamples);
  const int width = scene.camera.width, height = scene.camera.height;

  RayCounts blocks;
  int differing = 0;
  std::uint64_t nonBackground = 0;
  auto compare = [&](const PixelXY& p, const Color& alone, const Color& together, const char* what) {
    if (std::memcmp(&alone, &together, sizeof alone) != 0 && ++differing <= 5)
      ADD_FAILURE() << what << " (" << p.x << ", " << p.y << "): alone " << alone.x << " " << alone.y << " " << alone.z
                    << ", in a block " << together.x << " " << together.y << " " << together.z;
    nonBackground += alone != scene.background;
  };
  for (int by = 0; by < height; by += 4)
    for (int bx = 0; bx < width; bx += 4) {
      PixelXY pixels[kRayPacket];
      int count = 0;
      for (int y = by; y < std::min(by + 4, height); ++y)
        for (int x = bx; x < std::min(bx + 4, width); ++x) pixels[count++] = {x, y};
      Color together[kRayPacket];
      tracer.tracePixels(pixels, count, together, blocks);
      for (int n = 0; n < count; ++n)
        compare(pixels[n], tracer.tracePixel(pixels[n].x, pixels[n].y, single), together[n], "pixel");
      if (pixelSamples > 1) {
        const int k = (bx + by) % pixelSamples;
        tracer.traceSamples(pixels, count, k, together, blocks);
        for (int n = 0; n < count; ++n)
          compare(pixels[n], tracer.traceSample(pixels[n].x, pixels[n].y, k, single), together[n], "sample");
      }
    }
  EXPECT_EQ(differing, 0);
  EXPECT_EQ(blocks.camera, single.camera);
  EXPECT_EQ(blocks.shadow, single.shadow);
  EXPECT_EQ(blocks.reflection, single.reflection);
  if (!scene.triangles.empty()) {
    EXPECT_GT(nonBackground, 0u);
  }
}

// The same on a conformance scene at 1/divisor of its resolution (keeps the test short; the scene's lights,
// mirrors and depth are its own).
void expectBlocksTraceAsSinglePixels(const std::filesystem::path& path, int pixelSamples, int divisor) {
  Scene scene = loadSceneFile(path).scene;
  scene.camera.width = std::max(1, scene.camera.width / divisor);
  scene.camera.height = std::max(1, scene.camera.height / divisor);
  RayCounts single;
  expectBlocksTraceAsSinglePixels(scene, pixelSamples, single);
}

TEST_P(Packets, BlocksOfPixelsTraceAsSinglePixels) { expectBlocksTraceAsSinglePixels(GetParam(), 1, 6); }

// 20 samples: a pixel's samples take two packets (16 and 4).
TEST_P(Packets, BlocksOfAntiAliasedPixelsTraceAsSinglePixels) { expectBlocksTraceAsSinglePixels(GetParam(), 20, 24); }

// The conformance scenes set <shadowrayepsilon>; the same without it (the robust offset, on whichever side the
// light is) and with secondary rays excluding the hit's triangle instead. Point-light shading takes each of the
// three its own way, four hits at a time (point_light_lanes.h).
TEST_P(Packets, BlocksTraceAsSinglePixelsWhereverSecondaryRaysStart) {
  Scene scene = loadSceneFile(GetParam()).scene;
  scene.camera.width = std::max(1, scene.camera.width / 8);
  scene.camera.height = std::max(1, scene.camera.height / 8);
  scene.shadowRayEpsilon.reset();
  RayCounts offset, excluding;
  expectBlocksTraceAsSinglePixels(scene, 1, offset, SecondaryRayStart::Offset);
  expectBlocksTraceAsSinglePixels(scene, 1, excluding, SecondaryRayStart::ExcludeHitTriangle);
}

// Facing mirrors, 40 bounces: the block follows its paths together to a fixed depth, then each lane alone; the
// pixels and ray counts are still the single pixels', and a depth of a million costs no more block memory.
TEST(PacketsOfDeepPaths, FinishAloneAndEqualSinglePixels) {
  Material mirror = testing::plainMaterial();
  mirror.mirror = Color(0.5f);
  Scene scene;
  scene.camera = testing::frontCamera(8);
  scene.materials.push_back(mirror);
  scene.maxRayDepth = 40;
  scene.ambientLight = Color(10.0f);
  scene.lights.of<PointLight>().push_back(PointLight{"1", {0.5, 0.5, -1.0}, Color(100.0f)});
  testing::addQuadFacingZ(scene, -10, -10, 10, 10, -2, 0);
  testing::addTriangle(scene, {-10, -10, 2}, {0, 10, 2}, {10, -10, 2}, 0);  // faces -z, behind the camera
  RayCounts single;
  expectBlocksTraceAsSinglePixels(scene, 1, single);
  EXPECT_GE(single.reflection, 2u * 40u);  // the central pixels bounce to the full depth, past the block's
}

GTEST_ALLOW_UNINSTANTIATED_PARAMETERIZED_TEST(Packets);
INSTANTIATE_TEST_SUITE_P(Conformance, Packets, ::testing::ValuesIn(testing::conformanceScenePaths()),
                         [](const ::testing::TestParamInfo<std::filesystem::path>& info) {
                           std::string name = info.param.stem().string();
                           for (char& c : name)
                             if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                           return name;
                         });

}  // namespace
}  // namespace rayview
