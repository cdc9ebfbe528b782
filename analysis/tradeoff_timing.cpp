#include "tradeoff_timing.h"

#include <time.h>

#include <algorithm>
#include <numeric>
#include <optional>

#include "rayview/grid_render.h"

namespace rayview {
namespace {

// CPU time of the whole process: with the pool's workers busy and the caller waiting, it is what the render
// threads got. Compared with wall time it tells whether other processes took the cores meanwhile.
double processCpuMs() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return t.tv_sec * 1e3 + t.tv_nsec * 1e-6;
}

bool traceGrid(const Tracer& tracer, int stride, ThreadPool& pool, const std::atomic<bool>* cancel, Image& image,
               RayCounts& rays) {
  return renderGrid(
      [&](const PixelXY* pixels, int count, Color* out, RayCounts& counts) {
        tracer.tracePixels(pixels, count, out, counts);
      },
      stride, 0, pool, image, rays, [cancel] { return cancel && cancel->load(std::memory_order_relaxed); },
      tracer.quantization());
}

}  // namespace

double msSince(TimingClock::time_point start) {
  return std::chrono::duration<double, std::milli>(TimingClock::now() - start).count();
}

double median(std::vector<double> values) {
  if (values.empty()) return 0.0;
  std::sort(values.begin(), values.end());
  const std::size_t n = values.size();
  return n % 2 == 1 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

bool renderOnce(const Tracer& tracer, int width, int height, int stride, ThreadPool& pool,
                const std::atomic<bool>* cancel, TimedRun& run) {
  run.image = Image(width, height);
  run.rays = {};
  const double cpuStart = processCpuMs();
  const auto start = TimingClock::now();
  if (!traceGrid(tracer, stride, pool, cancel, run.image, run.rays)) return false;
  run.wallMs = msSince(start);
  run.cpuShare = run.wallMs > 0.0 ? (processCpuMs() - cpuStart) / (run.wallMs * pool.size()) : 1.0;
  fillBlocks(run.image, stride);
  return true;
}

std::vector<double> timeInTurn(std::span<const QuickRender> renders, int width, int height, ThreadPool& pool,
                               const std::atomic<bool>* cancel) {
  if (renders.empty()) return {};
  std::vector<std::size_t> order(renders.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return renders[a].accel < renders[b].accel; });
  std::vector<std::vector<double>> timesMs(renders.size());
  Image scratch(width, height);  // the images were kept from the first render of each
  std::optional<AccelKind> previousAccel;
  const auto start = TimingClock::now();
  for (int turn = 0; turn < kMinTurns || msSince(start) < kMinTimedMs; ++turn) {
    for (const std::size_t k : order) {
      const QuickRender& r = renders[k];
      RayCounts rays;
      if (previousAccel != r.accel && !traceGrid(*r.tracer, r.stride, pool, cancel, scratch, rays)) return {};
      previousAccel = r.accel;
      const auto renderStart = TimingClock::now();
      if (!traceGrid(*r.tracer, r.stride, pool, cancel, scratch, rays)) return {};
      timesMs[k].push_back(msSince(renderStart));
    }
  }
  std::vector<double> fastest;
  for (const std::vector<double>& times : timesMs) fastest.push_back(*std::min_element(times.begin(), times.end()));
  return fastest;
}

}  // namespace rayview
