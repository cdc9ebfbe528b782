#include "rayview/grid_render.h"

#include <algorithm>
#include <atomic>
#include <cstring>
#include <mutex>

#include "rayview/tiles.h"

namespace rayview {
namespace {

int ceilDiv(int a, int b) { return (a + b - 1) / b; }

constexpr int kBlock = 4;  // kBlock x kBlock = kPixelBatch
static_assert(kBlock * kBlock == kPixelBatch);

// The one order a tile's pixels are traced in. Bands of kBlock rows, column by column: a full batch is a 4x4
// block, or, where a coarser pass's pixels are skipped (a quarter of them), the next columns' pixels fill it
// (about 4 x 5): packets stay full. `endBand` runs after each band.
template <class Visit, class EndBand>
void visitTilePixels(const Tile& tile, int stride, int skipStride, Visit&& visit, EndBand&& endBand) {
  for (int by = tile.y0; by < tile.y1; by += kBlock) {
    for (int gx = tile.x0; gx < tile.x1; ++gx)
      for (int gy = by; gy < std::min(by + kBlock, tile.y1); ++gy) {
        const int x = gx * stride, y = gy * stride;
        if (skipStride != 0 && x % skipStride == 0 && y % skipStride == 0) continue;
        visit(x, y);
      }
    endBand();
  }
}

}  // namespace

void gridTilePixels(const Tile& tile, int stride, int skipStride, std::vector<PixelXY>& out) {
  out.clear();
  visitTilePixels(tile, stride, skipStride, [&](int x, int y) { out.push_back({x, y}); }, [] {});
}

void traceColors(const PixelBatchFunction& trace, const std::vector<PixelXY>& pixels, ThreadPool& pool,
                 std::vector<Color>& colors, RayCounts& rays) {
  colors.resize(pixels.size());
  // Chunks of whole batches, a few per thread: the list is in batch order already.
  const std::size_t chunk = static_cast<std::size_t>(kPixelBatch) * 8;
  std::mutex raysMutex;
  pool.parallelFor((pixels.size() + chunk - 1) / chunk, [&](std::size_t index) {
    RayCounts counts;
    const std::size_t end = std::min(pixels.size(), (index + 1) * chunk);
    for (std::size_t at = index * chunk; at < end; at += kPixelBatch) {
      const int count = static_cast<int>(std::min<std::size_t>(kPixelBatch, end - at));
      trace(pixels.data() + at, count, colors.data() + at, counts);
    }
    std::lock_guard lock(raysMutex);
    rays += counts;
  });
}

bool renderGrid(const PixelBatchFunction& pixels, int stride, int skipStride, ThreadPool& pool, Image& image,
                RayCounts& rays, const std::function<bool()>& stopped, Quantization quantization,
                const std::function<void(std::int64_t pixels)>& tileDone) {
  const std::vector<Tile> tiles = makeTiles(ceilDiv(image.width, stride), ceilDiv(image.height, stride), pool.size());
  std::mutex raysMutex;
  std::atomic<bool> cancelled{false};
  // Held in locals: through the references, every byte stored below would make them be read again.
  std::uint8_t* const rgb = image.rgb.data();
  const std::size_t width = static_cast<std::size_t>(image.width);
  const Quantization quantize = quantization;
  pool.parallelFor(tiles.size(), [&, rgb, width, quantize](std::size_t index) {
    if (stopped && stopped()) {
      cancelled.store(true, std::memory_order_relaxed);
      return;
    }
    const Tile& tile = tiles[index];
    RayCounts counts;
    PixelXY batch[kPixelBatch];
    Color colors[kPixelBatch];
    int count = 0;
    std::int64_t traced = 0;
    auto flush = [&] {
      if (count == 0) return;
      pixels(batch, count, colors, counts);
      for (int n = 0; n < count; ++n) {
        std::uint8_t* out = rgb + (static_cast<std::size_t>(batch[n].y) * width + static_cast<std::size_t>(batch[n].x)) * 3;
        out[0] = quantizeChannel(colors[n].x, quantize);
        out[1] = quantizeChannel(colors[n].y, quantize);
        out[2] = quantizeChannel(colors[n].z, quantize);
      }
      traced += count;
      count = 0;
    };
    visitTilePixels(tile, stride, skipStride, [&](int x, int y) {
      batch[count++] = {x, y};
      if (count == kPixelBatch) flush();
    }, flush);
    if (tileDone) tileDone(traced);
    std::lock_guard lock(raysMutex);
    rays += counts;
  });
  return !cancelled.load();
}

void fillBlocks(Image& image, int stride) {
  if (stride <= 1) return;
  // In place: a block's sample is read before anything in its row overwrites it; rows between grid rows
  // copy the finished row above.
  const auto rowBytes = static_cast<std::size_t>(image.width) * 3;
  for (int y = 0; y < image.height; ++y) {
    std::uint8_t* row = image.pixel(0, y);
    if (y % stride != 0) {
      std::memcpy(row, image.pixel(0, y - 1), rowBytes);
      continue;
    }
    for (int x = 0; x < image.width; ++x)
      if (x % stride != 0) std::memcpy(row + 3 * x, row + 3 * (x - x % stride), 3);
  }
}

Image gridSamples(const Image& image, int stride) {
  Image samples;
  copyGridSamples(image, stride, samples);
  return samples;
}

void copyGridSamples(const Image& image, int stride, Image& samples) {
  stride = std::max(stride, 1);
  samples.width = ceilDiv(image.width, stride);
  samples.height = ceilDiv(image.height, stride);
  if (stride == 1) {
    samples.rgb.assign(image.rgb.begin(), image.rgb.end());  // within the old capacity: no allocation
    return;
  }
  samples.rgb.resize(static_cast<std::size_t>(samples.width) * samples.height * 3);
  for (int gy = 0; gy < samples.height; ++gy)
    for (int gx = 0; gx < samples.width; ++gx) std::memcpy(samples.pixel(gx, gy), image.pixel(gx * stride, gy * stride), 3);
}

Image upscaleBlocks(const Image& samples, int stride, int width, int height) {
  if (stride <= 1) return samples;
  Image image(width, height);
  const auto rowBytes = static_cast<std::size_t>(width) * 3;
  for (int y = 0; y < height; ++y) {
    std::uint8_t* row = image.pixel(0, y);
    if (y % stride != 0) {
      std::memcpy(row, image.pixel(0, y - 1), rowBytes);
      continue;
    }
    for (int x = 0; x < width; ++x) std::memcpy(row + 3 * x, samples.pixel(x / stride, y / stride), 3);
  }
  return image;
}

}  // namespace rayview
