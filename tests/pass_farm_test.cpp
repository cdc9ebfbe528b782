// Passes traced by a farm (rayview/pass_farm.h; under MPI, the other ranks): the final frame is the headless render
// bit for bit whatever order and pace the pieces arrive in, and a slow full-resolution pass is shown as it arrives.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <mutex>
#include <thread>
#include <vector>

#include "rayview/frame_renderer.h"
#include "rayview/grid_render.h"
#include "rayview/pass_farm.h"
#include "rayview/pixel_source.h"
#include "rayview/prepared_scene.h"
#include "rayview/progressive_renderer.h"
#include "rayview/scene_loader.h"
#include "rayview/scene_source.h"

namespace rayview {
namespace {

using namespace std::chrono_literals;

// Traces on its own pool, tiles in reverse order (the opposite of the local render's), pausing after each.
class ReversedFarm final : public PassFarm {
 public:
  explicit ReversedFarm(std::chrono::milliseconds pause) : pool_(2), pause_(pause) {}
  bool accepts(const PixelSource&) const override { return true; }
  bool renderPass(const PixelSource& source, const FarmPass& pass, const FarmSink& sink,
                  const std::function<bool()>& stopped, RayCounts& rays) override {
    ++passes;
    std::vector<Tile> tiles = tilesOfEdge((source.width() + pass.stride - 1) / pass.stride,
                                          (source.height() + pass.stride - 1) / pass.stride, 8);
    std::reverse(tiles.begin(), tiles.end());
    std::vector<PixelXY> pixels;
    std::vector<Color> colors;
    for (const Tile& tile : tiles) {
      if (stopped()) return false;
      gridTilePixels(tile, pass.stride, pass.skipStride, pixels);
      traceColors(farmTrace(source, pass.sample), pixels, pool_, colors, rays);
      sink(pixels.data(), colors.data(), static_cast<int>(pixels.size()));
      std::this_thread::sleep_for(pause_);
    }
    return true;
  }
  std::atomic<int> passes{0};

 private:
  ThreadPool pool_;
  std::chrono::milliseconds pause_;
};

struct Fixture {
  std::shared_ptr<const Scene> scene;
  std::shared_ptr<const PreparedGeometry> geometry;
  RenderSettings settings;
  Image headless;
};

Fixture makeFixture(int pixelSamples) {
  LoadedScene loaded = loadSceneText(defaultSceneXml(), "default scene", ".");
  loaded.scene.camera.width = 90;  // not a multiple of the coarse strides
  loaded.scene.camera.height = 70;
  Fixture f;
  f.settings.pixelSamples = pixelSamples;
  f.settings.lightSamples = 2;
  f.scene = std::make_shared<const Scene>(std::move(loaded.scene));
  f.geometry = prepareGeometry(f.scene, f.settings.accel, BvhBuild::Interactive);
  const Tracer tracer(*f.scene, *f.geometry->accel, f.geometry->shading, f.settings);
  ThreadPool pool(2);
  FrameStats stats;
  EXPECT_TRUE(renderFrame(tracer, f.scene->camera.width, f.scene->camera.height, pool, f.headless, stats));
  return f;
}

std::shared_ptr<const PixelSource> sourceOf(const Fixture& f) {
  return std::make_shared<TracedImage>(std::make_shared<const SceneParameters>(f.scene->parameters()), f.geometry,
                                       f.settings);
}

TEST(PassFarm, TheFinalFrameIsTheHeadlessRenderWhateverOrderThePiecesArriveIn) {
  for (const int samples : {1, 3}) {
    const Fixture f = makeFixture(samples);
    auto farm = std::make_shared<ReversedFarm>(0ms);
    ProgressiveRenderer renderer(2, farm);
    const auto generation = renderer.restart(sourceOf(f));
    ASSERT_TRUE(renderer.waitForFinal(generation, 60s));
    ProgressiveFrame frame;
    ASSERT_TRUE(renderer.takeFrameIfNewer(0, frame));
    EXPECT_TRUE(frame.final);
    EXPECT_FALSE(frame.partial);
    EXPECT_EQ(frame.image.rgb, f.headless.rgb) << samples << " samples a pixel";
    EXPECT_GE(farm->passes.load(), samples) << "the farm traced the passes, not the renderer's own pool";
  }
}

TEST(PassFarm, ASlowFullResolutionPassIsShownAsItsPiecesArrive) {
  const Fixture f = makeFixture(1);
  // About 100 tiles at full resolution, 10 ms apart: a second, published every 100 ms.
  auto farm = std::make_shared<ReversedFarm>(10ms);
  ProgressiveRenderer renderer(2, farm);
  std::mutex mutex;
  std::vector<ProgressiveFrame> partial;
  renderer.setFrameListener([&] {
    ProgressiveFrame frame;
    if (!renderer.takeFrameIfNewer(0, frame) || !frame.partial) return;
    std::lock_guard lock(mutex);
    partial.push_back(std::move(frame));
  });
  const auto generation = renderer.restart(sourceOf(f));
  ASSERT_TRUE(renderer.waitForFinal(generation, 60s));
  std::lock_guard lock(mutex);
  ASSERT_GE(partial.size(), 2u) << "the pass is shown while it arrives";
  for (const ProgressiveFrame& frame : partial) {
    EXPECT_EQ(frame.stride, 1);
    EXPECT_FALSE(frame.final);
    EXPECT_EQ(frame.image.width, f.headless.width);
  }
  // Early on, part of the image is already the final one and part is not yet.
  const Image& early = partial.front().image;
  std::size_t same = 0;
  for (std::size_t i = 0; i < early.rgb.size(); i += 3)
    same += std::equal(early.rgb.begin() + i, early.rgb.begin() + i + 3, f.headless.rgb.begin() + i);
  EXPECT_GT(same, 0u);
  EXPECT_LT(same, early.rgb.size() / 3);
}

TEST(PassFarm, AnEditMidPassDropsThePassAndTheNextOneIsExact) {
  const Fixture f = makeFixture(1);
  auto farm = std::make_shared<ReversedFarm>(5ms);
  ProgressiveRenderer renderer(2, farm);
  renderer.restart(sourceOf(f));
  std::this_thread::sleep_for(30ms);
  const auto generation = renderer.restart(sourceOf(f));
  ASSERT_TRUE(renderer.waitForFinal(generation, 60s));
  ProgressiveFrame frame;
  ASSERT_TRUE(renderer.takeFrameIfNewer(0, frame));
  EXPECT_EQ(frame.generation, generation);
  EXPECT_EQ(frame.image.rgb, f.headless.rgb);
}

}  // namespace
}  // namespace rayview
