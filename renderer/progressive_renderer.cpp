#include "rayview/progressive_renderer.h"

#include <cstdio>
#include <new>

#include <algorithm>

#include "rayview/grid_render.h"

namespace rayview {
namespace {

using Clock = std::chrono::steady_clock;

double msBetween(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration<double, std::milli>(b - a).count();
}

}  // namespace

ProgressiveRenderer::ProgressiveRenderer(int threads, std::shared_ptr<PassFarm> farm)
    : pool_(threads), farm_(std::move(farm)) {
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
      restartTime_ = restartTime;
      busy_ = true;
    }
    const bool final = [&] {
     try {
      if (!source || source->width() <= 0 || source->height() <= 0) return false;
      const int width = source->width(), height = source->height();
      if (samples_.width != width || samples_.height != height) samples_ = Image(width, height);
      const int firstStride = interactive_.load() ? choosePreviewStride(passTimes_, width, height, kDragPassBudgetMs)
                                                  : chooseEditStride(passTimes_, width, height);
      firstStride_.store(firstStride);
      // Anti-aliasing: the coarse-to-fine passes trace each pixel's first sample, then one pass per further
      // sample adds it to the running sums, until the last makes the mean `rayview render` computes.
      const int pixelSamples = std::max(source->samplesPerPixel(), 1);
      if (pixelSamples > 1) sums_.resize(static_cast<std::size_t>(width) * height);
      // While the user drags, hold each pass until the drag ends or the next edit arrives.
      auto holdWhileDragging = [&] {
        std::unique_lock lock(mutex_);
        changed_.wait(lock, [&] { return stopping_ || generation_.load() != generation || !interactive_.load(); });
        return generation_.load() == generation;
      };
      int previousStride = 0;
      for (int stride = firstStride; stride >= 1; previousStride = stride, stride = nextPassStride(firstStride, stride)) {
        const auto passStart = Clock::now();
        RayCounts rays;
        const bool complete = renderPass(*source, generation, stride, previousStride, pixelSamples > 1, rays);
        const double passMs = msBetween(passStart, Clock::now());
        // The pixels on the previous pass's grid were not traced again.
        const std::int64_t traced =
            levelPixels(width, height, stride) - (previousStride > 0 ? levelPixels(width, height, previousStride) : 0);
        remember({stride, traced, passMs, complete});
        if (!complete) return false;
        publish(generation, stride, {1, pixelSamples}, passMs, rays, restartTime);
        if (stride == 1 && pixelSamples == 1) return true;
        if (!holdWhileDragging()) return false;
      }
      for (int k = 1; k < pixelSamples; ++k) {
        const auto passStart = Clock::now();
        RayCounts rays;
        if (!accumulatePass(*source, generation, k, rays)) return false;
        publish(generation, 1, {k + 1, pixelSamples}, msBetween(passStart, Clock::now()), rays, restartTime);
        if (k + 1 == pixelSamples) return true;
        if (!holdWhileDragging()) return false;
      }
      return false;
     } catch (const std::bad_alloc&) {
      // Out of memory on this thread or a worker (the pool hands it back): this render stops, never the process;
      // the next edit tries again.
      std::fprintf(stderr, "rayview: out of memory: the render stopped\n");
      samples_ = Image();
      std::vector<Color>().swap(sums_);
      return false;
     }
    }();
    {
      std::lock_guard lock(mutex_);
      busy_ = false;
      if (final && generation_.load() == generation) finalGeneration_ = generation;
    }
    changed_.notify_all();
  }
}

PassProgress ProgressiveRenderer::passProgress() const {
  PassProgress p;
  p.generation = passGeneration_.load(std::memory_order_relaxed);
  p.stride = passStride_.load(std::memory_order_relaxed);
  const std::int64_t planned = passPixelsPlanned_.load(std::memory_order_relaxed);
  if (planned > 0)
    p.fraction = std::min(1.0, static_cast<double>(passPixelsDone_.load(std::memory_order_relaxed)) / planned);
  return p;
}

std::function<void(std::int64_t)> ProgressiveRenderer::tileCounter() {
  return [this](std::int64_t pixels) { passPixelsDone_.fetch_add(pixels, std::memory_order_relaxed); };
}

void ProgressiveRenderer::startCounting(std::uint64_t generation, int stride, std::int64_t pixels) {
  passPixelsDone_.store(0, std::memory_order_relaxed);
  passPixelsPlanned_.store(pixels, std::memory_order_relaxed);
  passStride_.store(stride, std::memory_order_relaxed);
  passGeneration_.store(generation, std::memory_order_relaxed);
}

bool ProgressiveRenderer::renderPass(const PixelSource& source, std::uint64_t generation, int stride,
                                     int previousStride, bool firstSamples, RayCounts& rays) {
  const auto stopped = [&] { return generation_.load(std::memory_order_relaxed) != generation; };
  const auto gridPixels = [&](int s) {
    return s <= 0 ? std::int64_t{0}
                  : static_cast<std::int64_t>((samples_.width + s - 1) / s) * ((samples_.height + s - 1) / s);
  };
  startCounting(generation, stride, gridPixels(stride) - gridPixels(previousStride));
  if (farm_ && farm_->accepts(source)) {
    // A full-resolution pass is shown as its tiles arrive: until then each pixel shows its block of the pass before.
    if (stride == 1 && previousStride > 1) fillBlocks(samples_, previousStride);
    return farmPass(source, {generation, stride, previousStride, firstSamples ? 0 : -1}, firstSamples,
                    {1, std::max(source.samplesPerPixel(), 1)}, rays);
  }
  // Pixels on the previous (coarser) pass's grid were computed by it: never twice.
  if (firstSamples) {
    // Each pixel is traced by one worker: its running sum is its own.
    renderGrid(
        [&](const PixelXY* pixels, int count, Color* out, RayCounts& counts) {
          source.samples(pixels, count, 0, out, counts);
          for (int n = 0; n < count; ++n)
            sums_[static_cast<std::size_t>(pixels[n].y) * samples_.width + pixels[n].x] = out[n];
        },
        stride, previousStride, pool_, samples_, rays, stopped, source.quantization(), tileCounter());
  } else {
    renderGrid(
        [&](const PixelXY* pixels, int count, Color* out, RayCounts& counts) {
          source.pixels(pixels, count, out, counts);
        },
        stride, previousStride, pool_, samples_, rays, stopped, source.quantization(), tileCounter());
  }
  return generation_.load() == generation;
}

bool ProgressiveRenderer::accumulatePass(const PixelSource& source, std::uint64_t generation, int k, RayCounts& rays) {
  const float count = static_cast<float>(k + 1);
  startCounting(generation, 1, static_cast<std::int64_t>(samples_.width) * samples_.height);
  if (farm_ && farm_->accepts(source))
    return farmPass(source, {generation, 1, 0, k}, true, {k, std::max(source.samplesPerPixel(), 1)}, rays);
  renderGrid(
      [&](const PixelXY* pixels, int n, Color* out, RayCounts& counts) {
        source.samples(pixels, n, k, out, counts);
        for (int m = 0; m < n; ++m) {
          Color& sum = sums_[static_cast<std::size_t>(pixels[m].y) * samples_.width + pixels[m].x];
          sum += out[m];
          out[m] = sum / count;  // after the last sample, the expression Tracer::tracePixel ends with
        }
      },
      1, 0, pool_, samples_, rays, [&] { return generation_.load(std::memory_order_relaxed) != generation; },
      source.quantization(), tileCounter());
  return generation_.load() == generation;
}

bool ProgressiveRenderer::farmPass(const PixelSource& source, const FarmPass& pass, bool keepSums, SampleCount shown,
                                   RayCounts& rays) {
  // Every pixel gets exactly what the local passes give it (the lambdas of renderPass and accumulatePass).
  const Quantization quantization = source.quantization();
  const float count = static_cast<float>(pass.sample + 1);
  const auto passStart = Clock::now();
  auto lastShown = passStart;
  constexpr auto kShowEvery = std::chrono::milliseconds(100);
  const FarmSink store = [&](const PixelXY* pixels, const Color* colors, int n) {
    for (int m = 0; m < n; ++m) {
      Color c = colors[m];
      if (keepSums) {
        Color& sum = sums_[static_cast<std::size_t>(pixels[m].y) * samples_.width + pixels[m].x];
        if (pass.sample > 0) {
          sum += c;
          c = sum / count;
        } else {
          sum = c;
        }
      }
      std::uint8_t* out = samples_.pixel(pixels[m].x, pixels[m].y);
      out[0] = quantizeChannel(c.x, quantization);
      out[1] = quantizeChannel(c.y, quantization);
      out[2] = quantizeChannel(c.z, quantization);
    }
    passPixelsDone_.fetch_add(n, std::memory_order_relaxed);
    const auto now = Clock::now();
    if (pass.stride == 1 && now - lastShown >= kShowEvery) {
      lastShown = now;
      publish(pass.generation, 1, shown, msBetween(passStart, now), rays, restartTime_, true);
    }
  };
  const auto stopped = [&] { return generation_.load(std::memory_order_relaxed) != pass.generation; };
  return farm_->renderPass(source, pass, store, stopped, rays) && generation_.load() == pass.generation;
}

void ProgressiveRenderer::publish(std::uint64_t generation, int stride, SampleCount samples, double passMs,
                                  const RayCounts& rays, Clock::time_point restartTime, bool partial) {
  ProgressiveFrame frame;
  frame.generation = generation;
  frame.stride = stride;
  frame.samples = samples;
  frame.partial = partial;
  frame.final = !partial && stride == 1 && samples.done == samples.total;
  frame.passMs = passMs;
  frame.passRays = rays;
  frame.megaRaysPerSecond = passMs > 0.0 ? rays.total() / (passMs * 1000.0) : 0.0;
  frame.width = samples_.width;
  frame.height = samples_.height;
  // Into the buffer of an earlier publication. At 6400x4000, on the shared 2-core machine, a fresh 77 MB
  // buffer for the final pass cost 250-1000 ms of page faults, and freeing the final pass's buffer when the
  // first move of a drag published its pass delayed that pass by 36-66 ms.
  frame.image = std::move(spareImage_);
  copyGridSamples(samples_, stride, frame.image);
  std::function<void()> listener;
  {
    std::lock_guard lock(mutex_);
    if (generation_.load() != generation) {  // stale: an edit arrived while this pass finished
      spareImage_ = std::move(frame.image);
      return;
    }
    frame.version = published_.version + 1;
    frame.msSinceRestart = msBetween(restartTime, Clock::now());
    if (published_.generation != generation) firstPassMs_ = frame.msSinceRestart;
    frame.firstPassMsSinceRestart = firstPassMs_;
    std::swap(published_, frame);
    listener = frameListener_;
  }
  spareImage_ = std::move(frame.image);
  if (listener) listener();
}

void ProgressiveRenderer::remember(const PassTime& pass) {
  // The choice reads back to the newest complete pass; a few more cover a run of cancelled ones.
  constexpr std::size_t kKept = 16;
  if (passTimes_.size() == kKept) passTimes_.erase(passTimes_.begin());
  passTimes_.push_back(pass);
}

}  // namespace rayview
