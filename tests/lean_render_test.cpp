// The lean layout (rayview/lean_memory.h) gives up memory, never a pixel: the image rendered in deflated bands is
// the image renderFrame makes, bit for bit and ray for ray, and prepareGeometry gives the lean packet BVH (whose
// answers tests/packet_test.cpp compares with Embree's) only to a lean build. Lean is chosen on request, or when the
// fast layout would not fit in the memory available; never by a scene's size alone.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <memory>
#include <string>
#include <utility>

#include "rayview/deflated_image.h"
#include "rayview/frame_renderer.h"
#include "rayview/lean_memory.h"
#include "rayview/prepared_scene.h"
#include "rayview/scene_source.h"
#include "support/scene_builder.h"
#include "support/test_meshes.h"

namespace rayview {
namespace {

// Auto is fast at every size that fits, lean only where the estimate does not fit; a request always wins.
TEST(LeanRender, AutoIsLeanOnlyWhenTheFastEstimateDoesNotFit) {
  const std::size_t pixels = 1920 * 1080;
  const std::uint64_t plenty = std::uint64_t{24} << 30;
  for (std::size_t triangles : {std::size_t{1}, std::size_t{99'999}, std::size_t{100'000}, std::size_t{999'999},
                                std::size_t{1'000'000}, std::size_t{10'000'000}})
    EXPECT_FALSE(planMemory(MemoryUse::Auto, triangles, pixels, plenty).lean) << triangles;
  const std::uint64_t estimate = estimatedFastPeakBytes(1'000'000, pixels);
  EXPECT_FALSE(planMemory(MemoryUse::Auto, 1'000'000, pixels, estimate).lean);
  const MemoryPlan tight = planMemory(MemoryUse::Auto, 1'000'000, pixels, estimate - 1);
  EXPECT_TRUE(tight.lean);
  EXPECT_NE(tight.reason.find("exceeds"), std::string::npos) << tight.reason;
  EXPECT_FALSE(planMemory(MemoryUse::Auto, 1'000'000, pixels, 0).lean) << "unknown memory: fast";
  EXPECT_TRUE(planMemory(MemoryUse::Lean, 10, pixels, plenty).lean);
  EXPECT_FALSE(planMemory(MemoryUse::Fast, 10'000'000, pixels, 1).lean);
  EXPECT_GT(estimatedFastPeakBytes(2'000'000, pixels), estimatedFastPeakBytes(1'000'000, pixels));
}

// The default scene (mirrors, a triangular light, every kind of ray) at a size whose last band and last chunk are
// short, on one thread and on three (three threads' bands are not two threads' bands).
TEST(LeanRender, DeflatedBandsHoldTheImageRenderFrameMakes) {
  Scene scene = loadSceneOrDefault("", {}).scene;
  scene.camera.width = 211;
  scene.camera.height = 301;
  const auto geometry = prepareGeometry(scene, AccelKind::Embree, BvhBuild::Interactive);
  const Tracer tracer(scene.parameters(), *geometry, RenderSettings{});
  for (int threads : {1, 3}) {
    SCOPED_TRACE(std::to_string(threads) + " threads");
    ThreadPool pool(threads);
    Image whole;
    FrameStats wholeStats;
    ASSERT_TRUE(renderFrame(tracer, scene.camera.width, scene.camera.height, pool, whole, wholeStats));
    DeflatedImage deflated;
    FrameStats deflatedStats;
    renderFrameDeflated(tracer, scene.camera.width, scene.camera.height, pool, deflated, deflatedStats);
    EXPECT_GT(deflated.chunks.size(), 2u);
    std::size_t held = 0;
    for (const std::string& chunk : deflated.chunks) held += chunk.size();
    EXPECT_LT(held, whole.rgb.size() / 2) << "the chunks are deflated";
    const Image inflated = deflated.inflate();
    EXPECT_EQ(inflated.width, whole.width);
    EXPECT_EQ(inflated.height, whole.height);
    EXPECT_TRUE(inflated.rgb == whole.rgb) << "pixels differ";
    EXPECT_EQ(deflatedStats.rays.camera, wholeStats.rays.camera);
    EXPECT_EQ(deflatedStats.rays.shadow, wholeStats.rays.shadow);
    EXPECT_EQ(deflatedStats.rays.reflection, wholeStats.rays.reflection);
  }
}

// Chunks that do not inflate to their rows are an error, not a wrong image.
TEST(LeanRender, ADeflatedImageWithDamagedOrMissingRowsIsAnError) {
  Image image(50, 70);
  for (std::size_t i = 0; i < image.rgb.size(); ++i) image.rgb[i] = static_cast<std::uint8_t>(i * 7);
  DeflatedImage deflated{image.width, image.height, 32, {}};
  for (int row = 0; row < image.height; row += 32)
    deflated.chunks.push_back(DeflatedImage::deflateRows(image.pixel(0, row), image.width, std::min(32, image.height - row)));
  ASSERT_EQ(deflated.chunks.size(), 3u);
  EXPECT_EQ(deflated.inflate().rgb, image.rgb);

  DeflatedImage missing = deflated;
  missing.chunks.pop_back();
  EXPECT_THROW(missing.inflate(), ImageIoError);
  DeflatedImage damaged = deflated;
  damaged.chunks[1][damaged.chunks[1].size() / 2] ^= 0x5A;
  EXPECT_THROW(damaged.inflate(), ImageIoError);
  DeflatedImage shortChunk = deflated;
  shortChunk.chunks[0] = DeflatedImage::deflateRows(image.pixel(0, 0), image.width, 31);
  EXPECT_THROW(shortChunk.inflate(), ImageIoError);
}

// A plane of n x n quads facing the camera.
Scene planeOfQuads(int n) {
  Scene scene;
  scene.camera = testing::frontCamera(16);
  scene.materials.push_back(testing::plainMaterial());
  testing::Placement placement;
  placement.centre = {0.0, 0.0, -3.0};
  testing::addTessellatedPlane(scene, placement, n, 0);
  return scene;
}

// A lean build gets the lean packet BVH where Embree is asked for, at any size; a fast build keeps Embree (the packet
// BVH only for small scenes), and the reference BVH asked for by name stays the reference BVH.
TEST(LeanRender, OnlyALeanBuildGetsTheLeanPacketBvh) {
  if (availableAccel(AccelKind::Embree) != AccelKind::Embree) GTEST_SKIP() << "built without Embree";
  const auto scene = std::make_shared<const Scene>(planeOfQuads(224));  // 100 352 triangles
  EXPECT_EQ(prepareGeometry(scene, AccelKind::Embree, BvhBuild::Lean)->accel->kind(), AccelKind::Packet);
  EXPECT_EQ(prepareGeometry(scene, AccelKind::Embree, BvhBuild::OneImage)->accel->kind(), AccelKind::Embree);
  EXPECT_EQ(prepareGeometry(scene, AccelKind::Embree, BvhBuild::Interactive)->accel->kind(), AccelKind::Embree) << "the viewer's call";
  const auto small = std::make_shared<const Scene>(planeOfQuads(20));  // 800
  EXPECT_EQ(prepareGeometry(small, AccelKind::Embree, BvhBuild::Lean)->accel->kind(), AccelKind::Packet);
  EXPECT_EQ(prepareGeometry(scene, AccelKind::Reference, BvhBuild::Lean)->accel->kind(), AccelKind::Reference);
}

}  // namespace
}  // namespace rayview
