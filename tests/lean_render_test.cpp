// Lean scenes (rayview/lean_memory.h) give up memory, never a pixel: the image rendered in deflated bands is the
// image renderFrame makes, bit for bit and ray for ray, and prepareGeometry gives the lean packet BVH (whose answers
// tests/packet_test.cpp compares with Embree's) to scenes from 1e5 to 1e6 triangles built for memory only.
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

static_assert(!isLeanScene(kLeanFromTriangles - 1) && isLeanScene(kLeanFromTriangles));
static_assert(isLeanScene(kLeanUntilTriangles - 1) && !isLeanScene(kLeanUntilTriangles));

// The default scene (mirrors, a triangular light, every kind of ray) at a size whose last band and last chunk are
// short, on one thread and on three (three threads' bands are not two threads' bands).
TEST(LeanRender, DeflatedBandsHoldTheImageRenderFrameMakes) {
  Scene scene = loadSceneOrDefault("", {}).scene;
  scene.camera.width = 211;
  scene.camera.height = 301;
  const auto geometry = prepareGeometry(scene, AccelKind::Embree);
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

// Built for memory (`rayview render`), a scene of the lean sizes gets the lean packet BVH where Embree is asked for;
// built for speed (the viewer, the analysis) it keeps Embree, and so does a scene under the lean sizes either way.
TEST(LeanRender, OnlyScenesBuiltForMemoryFromOneHundredThousandTrianglesGetTheLeanPacketBvh) {
  if (availableAccel(AccelKind::Embree) != AccelKind::Embree) GTEST_SKIP() << "built without Embree";
  const auto lean = std::make_shared<const Scene>(planeOfQuads(224));  // 100 352 triangles
  ASSERT_TRUE(isLeanScene(lean->triangles.size()));
  EXPECT_EQ(prepareGeometry(lean, AccelKind::Embree, BuildPriority::Memory)->accel->kind(), AccelKind::Packet);
  EXPECT_EQ(prepareGeometry(lean, AccelKind::Embree, BuildPriority::Speed)->accel->kind(), AccelKind::Embree);
  EXPECT_EQ(prepareGeometry(lean, AccelKind::Embree)->accel->kind(), AccelKind::Embree) << "the viewer's call";
  const auto below = std::make_shared<const Scene>(planeOfQuads(200));  // 80 000, as the largest conformance scene
  ASSERT_FALSE(isLeanScene(below->triangles.size()));
  EXPECT_EQ(prepareGeometry(below, AccelKind::Embree, BuildPriority::Memory)->accel->kind(), AccelKind::Embree);
  // Asked for by name, the reference BVH is still the reference BVH.
  EXPECT_EQ(prepareGeometry(lean, AccelKind::Reference, BuildPriority::Memory)->accel->kind(), AccelKind::Reference);
}

}  // namespace
}  // namespace rayview
