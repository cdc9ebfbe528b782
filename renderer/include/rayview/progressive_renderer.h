#pragma once
// Coarse-to-fine rendering in the background (the viewer's engine; no GL here).
//
// A first pass at a coarse stride (its preview level), then full resolution, with one level between for very
// coarse starts (nextPassStride). The first pass's stride is chosen at each restart from the passes just
// measured (rayview/preview_level.h): the whole frame when it fits kWholeFrameFirstPassMs, else the finest
// level that fits kFirstPassBudgetMs, or kDragPassBudgetMs while the user drags. Each stride divides the one
// before, and a pass computes only the pixels on its stride grid that the previous pass's grid lacks, so every pixel is computed exactly once and the final pass equals `rayview render`
// bit for bit, whatever the first level was. A coarse pass is published as its samples only, one pixel
// per block (drawn enlarged with nearest filtering it is the blocky upscale, never a blur): a full-size copy
// per pass cost about 250 ms at 6400x4000, copying it to the UI and uploading it more.
//
// With N anti-aliasing samples per pixel (RenderSettings::pixelSamples), those passes trace each pixel's first
// sample; then N - 1 full-resolution passes each add one more to a running float sum per pixel and publish
// the mean so far. The sums are added in the order Tracer::tracePixel adds them, so the last pass is still
// `rayview render` bit for bit. The sums cost 12 bytes per pixel, only when N > 1.
//
// Cancellation by generation: restart() bumps the generation and returns at once; workers check it per
// tile; a pass whose generation is stale is never published. The UI thread never renders and never waits.

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

#include "rayview/image.h"
#include "rayview/pass_farm.h"
#include "rayview/pixel_source.h"
#include "rayview/preview_level.h"
#include "rayview/thread_pool.h"

namespace rayview {

// Anti-aliasing samples per pixel: traced so far (every pixel alike) of the setting's total.
struct SampleCount {
  int done = 1;
  int total = 1;
};

// The pass being rendered: its generation and stride, and the share of its pixels done (0 to 1).
struct PassProgress {
  std::uint64_t generation = 0;
  int stride = 0;  // 0: none running
  double fraction = 0.0;
};

struct ProgressiveFrame {
  std::uint64_t version = 0;     // increases with every published frame
  std::uint64_t generation = 0;  // the restart this frame belongs to
  int stride = 0;                // 1 = full resolution
  SampleCount samples;           // at stride 1, the passes after the first add one sample per pixel each
  bool final = false;            // all pixels computed, with all their samples
  // A full-resolution pass still arriving from a PassFarm, published as its tiles come in: the pixels not in yet
  // show the pass before (its blocks, or the mean of fewer samples).
  bool partial = false;
  int width = 0, height = 0;     // the image's size
  // The pass's samples, one pixel per stride x stride block: ceil(width / stride) x ceil(height / stride); at
  // stride 1, the image. upscaleBlocks (rayview/grid_render.h) makes the full-size blocky image.
  Image image;
  double passMs = 0.0;           // time of the pass that completed this frame
  double msSinceRestart = 0.0;   // from restart() to this frame's publication
  double firstPassMsSinceRestart = 0.0;  // from restart() to the first pass of this generation
  RayCounts passRays;
  double megaRaysPerSecond = 0.0;  // of that pass
};

class ProgressiveRenderer {
 public:
  // With a farm, passes of the sources it accepts are traced by it (other processes) instead of this pool.
  explicit ProgressiveRenderer(int threads = 0, std::shared_ptr<PassFarm> farm = nullptr);
  ~ProgressiveRenderer();
  ProgressiveRenderer(const ProgressiveRenderer&) = delete;
  ProgressiveRenderer& operator=(const ProgressiveRenderer&) = delete;

  // Cancels the running render (without waiting) and starts `source` from its first pass.
  // Returns the new generation. A null source just cancels.
  std::uint64_t restart(std::shared_ptr<const PixelSource> source);

  // Called on the renderer's thread after each publication (the viewer posts an empty event to wake its
  // UI loop, so it can sleep while a pass renders). Must be cheap and thread-safe. Set it before restart().
  void setFrameListener(std::function<void()> listener);

  // While true (the user is dragging), only the first pass of each restart is rendered, at the finest level
  // that fits kDragPassBudgetMs.
  void setInteractive(bool interactive);

  // Copies the newest complete frame into `out` if its version is newer than `haveVersion`.
  bool takeFrameIfNewer(std::uint64_t haveVersion, ProgressiveFrame& out) const;

  std::uint64_t generation() const { return generation_.load(); }
  bool idle() const;   // nothing queued or running
  int threads() const { return pool_.size(); }

  // Blocks until the render of `generation` is final or superseded (tests, automation). Returns true if final.
  bool waitForFinal(std::uint64_t generation, std::chrono::milliseconds timeout) const;

  // The stride the newest restart started with (chosen from measured pass times).
  int firstStride() const { return firstStride_.load(); }
  // How far the pass in flight is (the viewer's progress bar for a long final pass). Relaxed reads: a hint.
  PassProgress passProgress() const;

 private:
  void controllerLoop();
  bool renderPass(const PixelSource& source, std::uint64_t generation, int stride, int previousStride,
                  bool firstSamples, RayCounts& rays);
  bool accumulatePass(const PixelSource& source, std::uint64_t generation, int k, RayCounts& rays);
  bool farmPass(const PixelSource& source, const FarmPass& pass, bool keepSums, SampleCount shown, RayCounts& rays);
  void publish(std::uint64_t generation, int stride, SampleCount samples, double passMs,
               const RayCounts& rays, std::chrono::steady_clock::time_point restartTime, bool partial = false);
  void remember(const PassTime& pass);

  ThreadPool pool_;
  std::shared_ptr<PassFarm> farm_;
  std::chrono::steady_clock::time_point restartTime_;  // of the generation being rendered; controller only
  std::atomic<std::uint64_t> generation_{0};
  std::atomic<bool> interactive_{false};
  std::atomic<int> firstStride_{kUnmeasuredStride};
  // The pass in flight: written by the controller when it starts one, counted by the workers per block.
  std::atomic<std::uint64_t> passGeneration_{0};
  std::atomic<int> passStride_{0};
  std::atomic<std::int64_t> passPixelsPlanned_{0}, passPixelsDone_{0};
  void startCounting(std::uint64_t generation, int stride, std::int64_t pixels);
  // What renderGrid calls with each finished tile's pixel count: the pass's progress, one atomic add a tile.
  std::function<void(std::int64_t)> tileCounter();

  mutable std::mutex mutex_;
  mutable std::condition_variable changed_;
  std::shared_ptr<const PixelSource> pending_;
  std::uint64_t pendingGeneration_ = 0;
  std::chrono::steady_clock::time_point pendingTime_;
  bool busy_ = false;
  bool stopping_ = false;

  // Written by the controller only while no pass of another generation can run.
  Image samples_;
  std::vector<Color> sums_;  // per pixel, the running sum of its anti-aliasing samples (only when there are several)
  std::vector<PassTime> passTimes_;  // the newest passes, oldest first
  Image spareImage_;                 // the buffer of the frame published before the newest, reused
  ProgressiveFrame published_;  // guarded by mutex_
  double firstPassMs_ = 0.0;     // of the generation being rendered; guarded by mutex_
  std::function<void()> frameListener_;  // guarded by mutex_
  std::uint64_t finalGeneration_ = 0;  // guarded by mutex_

  std::thread controller_;
};

}  // namespace rayview
