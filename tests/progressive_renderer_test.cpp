// The pass scheduler: cancellation by generation, exactly-once pixels, no stale frame ever published.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <future>
#include <thread>

#include <atomic>
#include <condition_variable>
#include <mutex>
#include <thread>

#include "rayview/frame_renderer.h"
#include "rayview/grid_render.h"
#include "rayview/pixel_source.h"
#include "rayview/prepared_scene.h"
#include "rayview/scene_loader.h"
#include "rayview/scene_source.h"
#include "rayview/progressive_renderer.h"

namespace rayview {
namespace {

using namespace std::chrono_literals;

// A pixel source that counts how often each pixel is computed; optionally blocks its first pixel until
// released, to hold the renderer mid-pass.
class CountingSource final : public PixelSource {
 public:
  CountingSource(int width, int height, float value, bool blockFirstPixel = false)
      : width_(width), height_(height), value_(value), counts_(static_cast<std::size_t>(width) * height),
        blocked_(blockFirstPixel) {}
  int width() const override { return width_; }
  int height() const override { return height_; }
  Color pixel(int x, int y, RayCounts& rays) const override {
    {
      std::unique_lock lock(mutex_);
      started_ = true;
      startedChanged_.notify_all();
      releaseChanged_.wait(lock, [&] { return !blocked_; });
    }
    counts_[static_cast<std::size_t>(y) * width_ + x].fetch_add(1);
    ++rays.camera;
    return Color(value_ + static_cast<float>((x * 7 + y * 13) % 50));
  }
  void waitUntilStarted() const {
    std::unique_lock lock(mutex_);
    startedChanged_.wait(lock, [&] { return started_; });
  }
  void release() const {
    std::lock_guard lock(mutex_);
    blocked_ = false;
    releaseChanged_.notify_all();
  }
  int count(int x, int y) const { return counts_[static_cast<std::size_t>(y) * width_ + x].load(); }
  long total() const {
    long sum = 0;
    for (const auto& c : counts_) sum += c.load();
    return sum;
  }

 private:
  int width_, height_;
  float value_;
  mutable std::vector<std::atomic<int>> counts_;
  mutable std::mutex mutex_;
  mutable std::condition_variable startedChanged_, releaseChanged_;
  mutable bool started_ = false;
  mutable bool blocked_;
};

ProgressiveFrame latest(const ProgressiveRenderer& renderer) {
  ProgressiveFrame frame;
  renderer.takeFrameIfNewer(0, frame);
  return frame;
}

// Passes from a first pass at `stride` down to full resolution: 64 -> 3 (64, 4, 1), 8 -> 2.
unsigned passesFrom(int stride) {
  unsigned passes = 1;
  for (int s = stride; s > 1; s = nextPassStride(stride, s)) ++passes;
  return passes;
}

TEST(ProgressiveRenderer, EveryPixelIsComputedExactlyOnceAndTheFinalFrameIsExact) {
  ProgressiveRenderer renderer(2);
  auto source = std::make_shared<CountingSource>(37, 23, 10.0f);  // sizes that are not multiples of 16
  const auto generation = renderer.restart(source);
  ASSERT_TRUE(renderer.waitForFinal(generation, 10s));
  for (int y = 0; y < 23; ++y)
    for (int x = 0; x < 37; ++x) ASSERT_EQ(source->count(x, y), 1) << x << "," << y;
  const ProgressiveFrame frame = latest(renderer);
  EXPECT_TRUE(frame.final);
  EXPECT_EQ(frame.stride, 1);
  EXPECT_EQ(frame.generation, generation);
  for (int y = 0; y < 23; ++y)
    for (int x = 0; x < 37; ++x) ASSERT_EQ(frame.image.pixel(x, y)[0], 10 + (x * 7 + y * 13) % 50);
}

// The viewer's bar for a long full-resolution pass: the pass counts every pixel it traces, up to all of them.
TEST(ProgressiveRenderer, TheFullPassCountsItsPixelsToTheEnd) {
  ProgressiveRenderer renderer(2);
  auto source = std::make_shared<CountingSource>(37, 23, 10.0f);
  const auto generation = renderer.restart(source);
  ASSERT_TRUE(renderer.waitForFinal(generation, 10s));
  const PassProgress pass = renderer.passProgress();
  EXPECT_EQ(pass.generation, generation);
  EXPECT_EQ(pass.stride, 1);
  EXPECT_DOUBLE_EQ(pass.fraction, 1.0);
}

TEST(ProgressiveRenderer, CoarsePassesPublishOneSamplePerBlockAndUpscaleToBlocks) {
  ProgressiveRenderer renderer(1);
  auto source = std::make_shared<CountingSource>(37, 23, 0.0f);  // partial blocks at the right and bottom
  renderer.setInteractive(true);  // hold the first (coarse) pass
  const auto generation = renderer.restart(source);
  ProgressiveFrame frame;
  for (int i = 0; i < 500 && !renderer.takeFrameIfNewer(0, frame); ++i) std::this_thread::sleep_for(2ms);
  ASSERT_EQ(frame.generation, generation);
  const int s = frame.stride;
  ASSERT_GT(s, 1);
  EXPECT_FALSE(frame.final);
  EXPECT_EQ(frame.width, 37);
  EXPECT_EQ(frame.height, 23);
  ASSERT_EQ(frame.image.width, (37 + s - 1) / s);
  ASSERT_EQ(frame.image.height, (23 + s - 1) / s);
  for (int gy = 0; gy < frame.image.height; ++gy)
    for (int gx = 0; gx < frame.image.width; ++gx)
      ASSERT_EQ(frame.image.pixel(gx, gy)[0], (gx * s * 7 + gy * s * 13) % 50) << gx << "," << gy;
  const Image blocks = upscaleBlocks(frame.image, s, frame.width, frame.height);
  ASSERT_EQ(blocks.width, 37);
  ASSERT_EQ(blocks.height, 23);
  for (int y = 0; y < 23; ++y)
    for (int x = 0; x < 37; ++x) {
      const int sx = x - x % s, sy = y - y % s;
      ASSERT_EQ(blocks.pixel(x, y)[0], (sx * 7 + sy * 13) % 50) << x << "," << y;
    }
  // Held while interactive: nothing finer arrives.
  std::this_thread::sleep_for(50ms);
  EXPECT_EQ(latest(renderer).stride, s);
  renderer.setInteractive(false);
  EXPECT_TRUE(renderer.waitForFinal(generation, 10s));
  EXPECT_EQ(latest(renderer).image.width, 37);
}

TEST(ProgressiveRenderer, CancelMidPassNeverPublishesTheStaleGeneration) {
  ProgressiveRenderer renderer(2);
  // Watch every publication as the viewer would, frame by frame.
  std::atomic<bool> watching{true};
  std::vector<std::uint64_t> seenGenerations;
  std::thread watcher([&] {
    ProgressiveFrame frame;
    std::uint64_t version = 0;
    // One look after the flag drops too: on a loaded machine this thread may not run at all
    // before the render ends, and the final frame must still be seen.
    for (bool more = true; more;) {
      more = watching.load();
      if (renderer.takeFrameIfNewer(version, frame)) {
        version = frame.version;
        seenGenerations.push_back(frame.generation);
      }
      if (more) std::this_thread::sleep_for(100us);
    }
  });
  auto first = std::make_shared<CountingSource>(64, 64, 0.0f, /*blockFirstPixel=*/true);
  const auto firstGeneration = renderer.restart(first);
  first->waitUntilStarted();  // the first pass is running and stuck
  auto second = std::make_shared<CountingSource>(64, 64, 100.0f);
  const auto secondGeneration = renderer.restart(second);
  EXPECT_GT(secondGeneration, firstGeneration);
  EXPECT_FALSE(renderer.waitForFinal(firstGeneration, 1s));  // superseded
  first->release();
  ASSERT_TRUE(renderer.waitForFinal(secondGeneration, 10s));
  const ProgressiveFrame frame = latest(renderer);
  EXPECT_EQ(frame.generation, secondGeneration);
  watching.store(false);
  watcher.join();
  ASSERT_FALSE(seenGenerations.empty());
  for (std::uint64_t g : seenGenerations) EXPECT_EQ(g, secondGeneration);
  // Versions count publications: at most the second render's passes.
  EXPECT_LE(frame.version, passesFrom(renderer.firstStride()));
  EXPECT_LT(first->total(), 64 * 64);  // the first render stopped early
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x) ASSERT_EQ(second->count(x, y), 1);
}

TEST(ProgressiveRenderer, AFinalFrameStartedFromTheCoarsestLevelIsStillExact) {
  ProgressiveRenderer renderer(2);
  // A first pass of 16 pixels held 100 ms before it was cancelled: pixels that slow make the next restart
  // start at the coarsest level.
  auto slow = std::make_shared<CountingSource>(64, 64, 0.0f, true);
  renderer.restart(slow);
  slow->waitUntilStarted();
  auto source = std::make_shared<CountingSource>(100, 70, 20.0f);
  const auto generation = renderer.restart(source);
  std::this_thread::sleep_for(100ms);
  slow->release();
  ASSERT_TRUE(renderer.waitForFinal(generation, 10s));
  EXPECT_EQ(renderer.firstStride(), kCoarsestStride);
  const ProgressiveFrame frame = latest(renderer);
  EXPECT_EQ(frame.version, passesFrom(kCoarsestStride));
  for (int y = 0; y < 70; ++y)
    for (int x = 0; x < 100; ++x) {
      ASSERT_EQ(source->count(x, y), 1) << x << "," << y;
      ASSERT_EQ(frame.image.pixel(x, y)[0], 20 + (x * 7 + y * 13) % 50) << x << "," << y;
    }
}

// A source whose every pixel takes at least `msPerPixel` (it sleeps): the slowest a scene can be, whatever the
// machine.
class SlowSource final : public PixelSource {
 public:
  SlowSource(int size, std::chrono::milliseconds msPerPixel) : size_(size), msPerPixel_(msPerPixel) {}
  int width() const override { return size_; }
  int height() const override { return size_; }
  Color pixel(int, int, RayCounts&) const override {
    std::this_thread::sleep_for(msPerPixel_);
    return Color(0.0f);
  }

 private:
  int size_;
  std::chrono::milliseconds msPerPixel_;
};

TEST(ProgressiveRenderer, WhileDraggingASlowSceneEachMoveShowsALevelCoarserThanTheDefault) {
  ProgressiveRenderer renderer(2);
  renderer.setInteractive(true);
  // The first move: nothing measured yet, the default level (16 pixels of 64x64, at least 32 ms on 2 threads).
  auto source = std::make_shared<SlowSource>(64, 4ms);
  auto waitForPassOf = [&](std::uint64_t generation) {
    ProgressiveFrame frame;
    for (int i = 0; i < 5000 && !(renderer.takeFrameIfNewer(0, frame) && frame.generation == generation); ++i)
      std::this_thread::sleep_for(2ms);
    return frame;
  };
  ProgressiveFrame first = waitForPassOf(renderer.restart(source));
  ASSERT_EQ(first.stride, kUnmeasuredStride);
  // The next moves: at least 2 ms a pixel does not fit 16 ms at 1/16; the level coarsens and stays coarse.
  for (int move = 0; move < 3; ++move) {
    const ProgressiveFrame frame = waitForPassOf(renderer.restart(source));
    EXPECT_GT(frame.stride, kUnmeasuredStride) << "move " << move;
    EXPECT_FALSE(frame.final);
  }
  renderer.restart(nullptr);
}

TEST(ProgressiveRenderer, ARestartSupersededBeforeItStartsComputesNothing) {
  ProgressiveRenderer renderer(2);
  auto blocker = std::make_shared<CountingSource>(32, 32, 0.0f, true);
  renderer.restart(blocker);
  blocker->waitUntilStarted();
  auto skipped = std::make_shared<CountingSource>(32, 32, 0.0f);
  renderer.restart(skipped);
  auto last = std::make_shared<CountingSource>(32, 32, 0.0f);
  const auto lastGeneration = renderer.restart(last);
  blocker->release();
  ASSERT_TRUE(renderer.waitForFinal(lastGeneration, 10s));
  EXPECT_EQ(skipped->total(), 0);
  EXPECT_EQ(last->total(), 32 * 32);
}

TEST(ProgressiveRenderer, CancelWithNullSourceStopsAndPublishesNothingNew) {
  ProgressiveRenderer renderer(2);
  auto blocker = std::make_shared<CountingSource>(32, 32, 0.0f, true);
  const auto generation = renderer.restart(blocker);
  blocker->waitUntilStarted();
  renderer.restart(nullptr);
  blocker->release();
  EXPECT_FALSE(renderer.waitForFinal(generation, 1s));
  for (int i = 0; i < 500 && !renderer.idle(); ++i) std::this_thread::sleep_for(2ms);
  EXPECT_TRUE(renderer.idle());
  ProgressiveFrame frame;
  EXPECT_FALSE(renderer.takeFrameIfNewer(0, frame));
}

TEST(ProgressiveRenderer, OnePixelImage) {
  ProgressiveRenderer renderer(2);
  auto source = std::make_shared<CountingSource>(1, 1, 42.0f);
  ASSERT_TRUE(renderer.waitForFinal(renderer.restart(source), 10s));
  EXPECT_EQ(latest(renderer).image.pixel(0, 0)[0], 42);
  EXPECT_EQ(source->total(), 1);
}

// The destructor runs on a thread of its own under a watchdog: a hang fails the test (and ends the process, since a
// hung thread cannot be joined) instead of stalling the suite until ctest's timeout.
TEST(ProgressiveRenderer, DestroyingWhileRenderingDoesNotHang) {
  auto source = std::make_shared<CountingSource>(512, 512, 0.0f);
  std::promise<void> destroyed;
  std::future<void> done = destroyed.get_future();
  std::thread destroyer([&] {
    {
      ProgressiveRenderer renderer(2);
      renderer.restart(source);
    }
    destroyed.set_value();
  });
  if (done.wait_for(60s) != std::future_status::ready) {
    ADD_FAILURE() << "destroying a renderer that is rendering did not return within 60 s";
    std::fflush(stdout);
    std::_Exit(1);
  }
  destroyer.join();
}

}  // namespace
}  // namespace rayview

namespace rayview {
namespace {

// Anti-aliasing in the viewer: after the coarse-to-fine passes of each pixel's first sample, one pass per
// further sample; every one is published with its count, and the last is `rayview render` bit for bit.
TEST(ProgressiveRenderer, AntiAliasingSamplesAccumulatePassByPassAndTheLastEqualsTheHeadlessRender) {
  LoadedScene loaded = loadSceneText(defaultSceneXml(), "default scene", ".");
  Scene& scene = loaded.scene;
  scene.camera.width = 96;  // small and not a multiple of the coarse strides
  scene.camera.height = 70;
  RenderSettings settings;
  settings.pixelSamples = 5;
  settings.lightSamples = 3;  // the light samples vary per camera ray: they must accumulate in order too
  auto shared = std::make_shared<const Scene>(scene);
  auto geometry = prepareGeometry(shared, settings.accel, BvhBuild::Interactive);
  const Tracer tracer(*shared, *geometry->accel, geometry->shading, settings);
  ThreadPool pool(2);
  Image headless;
  FrameStats stats;
  ASSERT_TRUE(renderFrame(tracer, scene.camera.width, scene.camera.height, pool, headless, stats));

  ProgressiveRenderer renderer(2);
  std::mutex mutex;
  std::vector<SampleCount> seen;
  Image firstSampleOnly;
  // Called on the controller after each publication, before the next pass: it sees every frame.
  renderer.setFrameListener([&] {
    ProgressiveFrame frame;
    if (!renderer.takeFrameIfNewer(0, frame)) return;
    std::lock_guard lock(mutex);
    if (frame.stride != 1) return;
    seen.push_back(frame.samples);
    if (frame.samples.done == 1) firstSampleOnly = frame.image;
  });
  auto source = std::make_shared<TracedImage>(std::make_shared<const SceneParameters>(scene.parameters()), geometry,
                                              settings);
  const std::uint64_t generation = renderer.restart(source);
  ASSERT_TRUE(renderer.waitForFinal(generation, 60s));
  ProgressiveFrame final;
  ASSERT_TRUE(renderer.takeFrameIfNewer(0, final));
  EXPECT_TRUE(final.final);
  EXPECT_EQ(final.samples.done, 5);
  EXPECT_EQ(final.samples.total, 5);
  EXPECT_EQ(final.image.rgb, headless.rgb) << "the last pass is the headless render, bit for bit";

  std::lock_guard lock(mutex);
  ASSERT_EQ(seen.size(), 5u) << "one full-resolution frame per sample";
  for (int k = 0; k < 5; ++k) EXPECT_EQ(seen[k].done, k + 1);
  // The first full-resolution frame holds one sample per pixel: the edges are not yet smoothed.
  EXPECT_NE(firstSampleOnly.rgb, headless.rgb);
}

}  // namespace
}  // namespace rayview
