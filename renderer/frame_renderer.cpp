#include "rayview/frame_renderer.h"

#include <chrono>

#include "rayview/grid_render.h"

namespace rayview {

bool renderFrame(const Tracer& tracer, int width, int height, ThreadPool& pool, Image& image, FrameStats& stats,
                 const std::atomic<bool>* stop) {
  const auto start = std::chrono::steady_clock::now();
  if (image.width != width || image.height != height) image = Image(width, height);
  stats.rays = {};
  const bool complete = renderGrid(
      [&](const PixelXY* pixels, int count, Color* out, RayCounts& counts) {
        tracer.tracePixels(pixels, count, out, counts);
      },
      1, 0, pool, image, stats.rays,
      [stop] { return stop && stop->load(std::memory_order_relaxed); });
  stats.renderMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return complete;
}

}  // namespace rayview
