#include "tile_render.h"

#include <cstring>

#include "rayview/grid_render.h"

namespace rayview::cluster {

void renderTile(const Tracer& tracer, const Tile& tile, ThreadPool& pool, Image& out, RayCounts& rays) {
  const int width = tile.x1 - tile.x0, height = tile.y1 - tile.y0;
  if (out.width != width || out.height != height) out = Image(width, height);
  renderGrid(
      [&](const PixelXY* pixels, int count, Color* colors, RayCounts& counts) {
        PixelXY inImage[kPixelBatch];
        for (int n = 0; n < count; ++n) inImage[n] = {pixels[n].x + tile.x0, pixels[n].y + tile.y0};
        tracer.tracePixels(inImage, count, colors, counts);
      },
      1, 0, pool, out, rays, nullptr, tracer.quantization());
}

void placeTile(const Tile& tile, const std::uint8_t* rgb, Image& image) {
  const auto rowBytes = static_cast<std::size_t>(tile.x1 - tile.x0) * 3;
  for (int y = tile.y0; y < tile.y1; ++y)
    std::memcpy(image.pixel(tile.x0, y), rgb + static_cast<std::size_t>(y - tile.y0) * rowBytes, rowBytes);
}

}  // namespace rayview::cluster
