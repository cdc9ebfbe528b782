#pragma once
// One tile of a distributed render, traced on this rank's thread pool.

#include "rayview/image.h"
#include "rayview/thread_pool.h"
#include "rayview/tiles.h"
#include "rayview/tracer.h"

namespace rayview::cluster {

// The tile's pixels, row by row, into `out` (resized to the tile): each pixel is the one renderFrame gives at
// its place in the image, bit for bit, since a pixel is a function of its coordinates only.
void renderTile(const Tracer& tracer, const Tile& tile, ThreadPool& pool, Image& out, RayCounts& rays);

// Copies a tile's pixels (`rgb`, the tile's rows) into the image at the tile's place.
void placeTile(const Tile& tile, const std::uint8_t* rgb, Image& image);

}  // namespace rayview::cluster
