#include "rayview/progressive_renderer.h"

#include <algorithm>
#include <cstring>

#include "rayview/tiles.h"

namespace rayview {
namespace {

using Clock = std::chrono::steady_clock;

double msBetween(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration<double, std::milli>(b - a).count();
}

int ceilDiv(int a, int b) { return (a + b - 1) / b; }

}  // namespace

ProgressiveRenderer::ProgressiveRenderer(int threads) : pool_(threads) {
  controller_ = std::thread([this] { controllerLoop(); });
}

ProgressiveRenderer::~ProgressiveRenderer() {
  {
    std::lock_guard lock(mutex_);
    stopping_ = true;
    ++generation_;  // running tiles stop at their next check
  }
  changed_.notify_all();
  controller_.join();
}

std::uint64_t ProgressiveRenderer::restart(std::shared_ptr<const PixelSource> source) {
  std::uint64_t generation;
  {
    std::lock_guard lock(mutex_);
    generation = ++generation_;
    pending_ = std::move(source);
    pendingGeneration_ = generation;
    pendingTime_ = Clock::now();
  }
  changed_.notify_all();
  return generation;
}

void ProgressiveRenderer::setFrameListener(std::function<void()> listener) {
  std::lock_guard lock(mutex_);
  frameListener_ = std::move(listener);
}

void ProgressiveRenderer::setInteractive(bool interactive) {
  {
    std::lock_guard lock(mutex_);
    interactive_.store(interactive);
  }
  changed_.notify_all();
}

bool ProgressiveRenderer::takeFrameIfNewer(std::uint64_t haveVersion, ProgressiveFrame& out) const {
  std::lock_guard lock(mutex_);
  if (published_.version <= haveVersion) return false;
  out = published_;
  return true;
}

bool ProgressiveRenderer::idle() const {
  std::lock_guard lock(mutex_);
  return !busy_ && !pending_;
}

bool ProgressiveRenderer::waitForFinal(std::uint64_t generation, std::chrono::milliseconds timeout) const {
  std::unique_lock lock(mutex_);
  changed_.wait_for(lock, timeout, [&] { return finalGeneration_ >= generation || generation_.load() > generation; });
  return finalGeneration_ >= generation;
}

void ProgressiveRenderer::controllerLoop() {
  for (;;) {
    std::shared_ptr<const PixelSource> source;
    std::uint64_t generation = 0;
    Clock::time_point restartTime;
    {
      std::unique_lock lock(mutex_);
      changed_.wait(lock, [&] { return stopping_ || pending_ != nullptr; });
      if (stopping_) return;
      source = std::move(pending_);
      pending_.reset();
      generation = pendingGeneration_;
      restartTime = pendingTime_;
      busy_ = true;
    }
    const bool final = [&] {
      if (!source || source->width() <= 0 || source->height() <= 0) return false;
      if (samples_.width != source->width() || samples_.height != source->height())
        samples_ = Image(source->width(), source->height());
      int previousStride = 0;
      for (int stride = firstStride_.load(); stride >= 1; previousStride = stride, stride /= 2) {
        const auto passStart = Clock::now();
        RayCounts rays;
        if (!renderPass(*source, generation, stride, previousStride, rays)) return false;
        const double passMs = msBetween(passStart, Clock::now());
        if (previousStride == 0) adaptFirstStride(stride, passMs);
        publish(*source, generation, stride, passMs, rays, restartTime);
        if (stride == 1) return true;
        // While the user drags, hold the coarse level until the drag ends or the next edit arrives.
        std::unique_lock lock(mutex_);
        changed_.wait(lock, [&] { return stopping_ || generation_.load() != generation || !interactive_.load(); });
        if (generation_.load() != generation) return false;
      }
      return false;
    }();
    {
      std::lock_guard lock(mutex_);
      busy_ = false;
      if (final && generation_.load() == generation) finalGeneration_ = generation;
    }
    changed_.notify_all();
  }
}

bool ProgressiveRenderer::renderPass(const PixelSource& source, std::uint64_t generation, int stride,
                                     int previousStride, RayCounts& rays) {
  const int gridWidth = ceilDiv(source.width(), stride);
  const int gridHeight = ceilDiv(source.height(), stride);
  const std::vector<Tile> tiles = makeTiles(gridWidth, gridHeight, pool_.size());
  std::mutex raysMutex;
  std::atomic<bool> cancelled{false};
  pool_.parallelFor(tiles.size(), [&](std::size_t index) {
    if (generation_.load(std::memory_order_relaxed) != generation) {
      cancelled.store(true, std::memory_order_relaxed);
      return;
    }
    const Tile& tile = tiles[index];
    RayCounts counts;
    for (int gy = tile.y0; gy < tile.y1; ++gy)
      for (int gx = tile.x0; gx < tile.x1; ++gx) {
        const int x = gx * stride, y = gy * stride;
        // Computed by an earlier pass of this restart: never twice.
        if (previousStride != 0 && x % previousStride == 0 && y % previousStride == 0) continue;
        const Color c = source.pixel(x, y, counts);
        std::uint8_t* out = samples_.pixel(x, y);
        out[0] = quantizeChannel(c.x);
        out[1] = quantizeChannel(c.y);
        out[2] = quantizeChannel(c.z);
      }
    std::lock_guard lock(raysMutex);
    rays += counts;
  });
  return !cancelled.load() && generation_.load() == generation;
}

void ProgressiveRenderer::publish(const PixelSource& source, std::uint64_t generation, int stride, double passMs,
                                  const RayCounts& rays, Clock::time_point restartTime) {
  ProgressiveFrame frame;
  frame.generation = generation;
  frame.stride = stride;
  frame.final = stride == 1;
  frame.passMs = passMs;
  frame.passRays = rays;
  frame.megaRaysPerSecond = passMs > 0.0 ? rays.total() / (passMs * 1000.0) : 0.0;
  const int width = source.width(), height = source.height();
  if (stride == 1) {
    frame.image = samples_;
  } else {
    // Each pixel shows the sample at the top-left corner of its stride block: blocky, no blur.
    frame.image = Image(width, height);
    for (int y = 0; y < height; ++y) {
      const std::uint8_t* sourceRow = samples_.pixel(0, y - y % stride);
      std::uint8_t* row = frame.image.pixel(0, y);
      if (y % stride != 0) {
        std::memcpy(row, frame.image.pixel(0, y - 1), static_cast<std::size_t>(width) * 3);
        continue;
      }
      for (int x = 0; x < width; ++x) std::memcpy(row + 3 * x, sourceRow + 3 * (x - x % stride), 3);
    }
  }
  std::function<void()> listener;
  {
    std::lock_guard lock(mutex_);
    if (generation_.load() != generation) return;  // stale: an edit arrived while this pass finished
    frame.version = published_.version + 1;
    frame.msSinceRestart = msBetween(restartTime, Clock::now());
    if (published_.generation != generation) firstPassMs_ = frame.msSinceRestart;
    frame.firstPassMsSinceRestart = firstPassMs_;
    published_ = std::move(frame);
    listener = frameListener_;
  }
  if (listener) listener();
}

void ProgressiveRenderer::adaptFirstStride(int stride, double passMs) {
  // A pass at stride s costs about (stride / s)^2 times this one. Pick the finest stride that fits the
  // budget, but refine by one step per restart only, so one cheap frame cannot make the next scene's first
  // pass slow; coarsen at once.
  int fitting = kCoarsestStride;
  for (int s = kCoarsestStride; s >= 1; s /= 2) {
    const double ratio = static_cast<double>(stride) / s;
    if (passMs * ratio * ratio <= kFirstPassBudgetMs) fitting = s;
  }
  firstStride_.store(fitting < stride ? stride / 2 : fitting);
}

}  // namespace rayview
