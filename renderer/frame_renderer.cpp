#include "rayview/frame_renderer.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <new>
#include <string>
#include <vector>

#include "rayview/grid_render.h"

namespace rayview {

bool renderFrame(const Tracer& tracer, int width, int height, ThreadPool& pool, Image& image, FrameStats& stats,
                 const std::atomic<bool>* stop) {
  const auto start = std::chrono::steady_clock::now();
  if (image.width != width || image.height != height) image = Image::unfilled(width, height);
  stats.rays = {};
  const bool complete = renderGrid(
      [&](const PixelXY* pixels, int count, Color* out, RayCounts& counts) {
        tracer.tracePixels(pixels, count, out, counts);
      },
      1, 0, pool, image, stats.rays,
      [stop] { return stop && stop->load(std::memory_order_relaxed); }, tracer.quantization());
  stats.renderMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return complete;
}

// Rows a chunk deflates: 180 KB of a 1920-pixel row's image, a few hundred microseconds of zlib.
constexpr int kChunkRows = 32;

void renderFrameDeflated(const Tracer& tracer, int width, int height, ThreadPool& pool, DeflatedImage& image,
                         FrameStats& stats) {
  const auto start = std::chrono::steady_clock::now();
  image = DeflatedImage{width, height, kChunkRows, {}};
  stats.rays = {};
  // Two chunks a thread to a band: the band's tiles keep every thread busy, and its chunks deflate at once.
  const int bandRows = kChunkRows * 2 * std::max(pool.size(), 1);
  Image band;
  for (int top = 0; top < height; top += bandRows) {
    const int rows = std::min(bandRows, height - top);
    if (band.height != rows || band.width != width) band = Image::unfilled(width, rows);
    renderGrid(
        [&](const PixelXY* pixels, int count, Color* out, RayCounts& counts) {
          PixelXY inImage[kPixelBatch];
          for (int n = 0; n < count; ++n) inImage[n] = {pixels[n].x, pixels[n].y + top};
          tracer.tracePixels(inImage, count, out, counts);
        },
        1, 0, pool, band, stats.rays, nullptr, tracer.quantization());
    const std::size_t chunks = static_cast<std::size_t>((rows + kChunkRows - 1) / kChunkRows);
    std::vector<std::string> deflated(chunks);
    std::atomic<bool> failed{false};
    pool.parallelFor(chunks, [&](std::size_t k) {
      const int first = static_cast<int>(k) * kChunkRows;
      try {
        deflated[k] = DeflatedImage::deflateRows(band.pixel(0, first), width, std::min(kChunkRows, rows - first));
      } catch (const std::bad_alloc&) {
        failed.store(true);
      }
    });
    if (failed.load()) throw std::bad_alloc();
    for (std::string& chunk : deflated) image.chunks.push_back(std::move(chunk));
  }
  stats.renderMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace rayview
