#include "rayview/frame_renderer.h"

#include <chrono>
#include <mutex>

#include "rayview/tiles.h"

namespace rayview {

bool renderFrame(const Tracer& tracer, int width, int height, ThreadPool& pool, Image& image, FrameStats& stats,
                 const std::atomic<bool>* stop) {
  const auto start = std::chrono::steady_clock::now();
  if (image.width != width || image.height != height) image = Image(width, height);
  const std::vector<Tile> tiles = makeTiles(width, height, pool.size());
  std::mutex countsMutex;
  RayCounts total;
  std::atomic<bool> cancelled{false};
  pool.parallelFor(tiles.size(), [&](std::size_t index) {
    if (stop && stop->load(std::memory_order_relaxed)) {
      cancelled.store(true, std::memory_order_relaxed);
      return;
    }
    const Tile& tile = tiles[index];
    RayCounts counts;
    for (int y = tile.y0; y < tile.y1; ++y)
      for (int x = tile.x0; x < tile.x1; ++x) {
        const Color c = tracer.tracePixel(x, y, counts);
        std::uint8_t* out = image.pixel(x, y);
        out[0] = quantizeChannel(c.x);
        out[1] = quantizeChannel(c.y);
        out[2] = quantizeChannel(c.z);
      }
    std::lock_guard lock(countsMutex);
    total += counts;
  });
  stats.rays = total;
  stats.renderMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return !cancelled.load();
}

}  // namespace rayview
