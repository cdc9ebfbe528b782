#pragma once
// The one tiled render loop: a full frame, a progressive pass and a tradeoff measurement all trace the
// pixels of a stride grid, tile by tile on the pool, centre first, and stop at the next tile when asked.

#include <cstdint>
#include <functional>
#include <vector>

#include "rayview/image.h"
#include "rayview/thread_pool.h"
#include "rayview/tiles.h"
#include "rayview/tracer.h"

namespace rayview {

// The colours of `count` pixels at once (out[n] for pixels[n]; count <= kPixelBatch): what lets a tracer cast
// their camera rays as one packet. renderGrid hands it 4x4 blocks of the grid (the most coherent), filled from
// the next columns where a coarser pass's pixels are skipped.
using PixelBatchFunction = std::function<void(const PixelXY* pixels, int count, Color* out, RayCounts& counts)>;
inline constexpr int kPixelBatch = kRayPacket;

// Traces the pixels (gx * stride, gy * stride) of `image` (already width x height) that are not also on the
// `skipStride` grid (0: skip none; a coarser pass computed those), quantizing into `image` as `quantization`
// says (the render settings'). `stopped` is checked before each tile. Returns false when it stopped early (the
// image is then partial). `tileDone`, when given, hears each finished tile's pixel count: progress counted once a
// tile, where an atomic add per batch of a cheap pass (two threads on one cache line) cost monkey's final pass 5 %.
bool renderGrid(const PixelBatchFunction& pixels, int stride, int skipStride, ThreadPool& pool, Image& image,
                RayCounts& rays, const std::function<bool()>& stopped, Quantization quantization,
                const std::function<void(std::int64_t pixels)>& tileDone = {});

// The pixels of `tile` (in grid coordinates) of that grid, less the skip grid's, in the order renderGrid traces
// them: what another process traces of a pass (rayview/pass_farm.h).
void gridTilePixels(const Tile& tile, int stride, int skipStride, std::vector<PixelXY>& out);
// Their radiance (colors[n] for pixels[n]) on the pool, kPixelBatch at a time, as renderGrid batches them.
void traceColors(const PixelBatchFunction& trace, const std::vector<PixelXY>& pixels, ThreadPool& pool,
                 std::vector<Color>& colors, RayCounts& rays);

// Gives every pixel the colour of the sample at the top-left corner of its stride x stride block: the
// blocky (never blurred) upscale of a coarse pass. In place.
void fillBlocks(Image& image, int stride);

// The samples of the stride grid of `image` (each block's top-left pixel), one pixel per block:
// ceil(width / stride) x ceil(height / stride). What a coarse pass publishes: far smaller than the image.
Image gridSamples(const Image& image, int stride);
// The same into `samples`, reusing its buffer when it is large enough.
void copyGridSamples(const Image& image, int stride, Image& samples);

// The other way: the width x height image in which every pixel shows its block's sample (what fillBlocks
// makes of the full-size image).
Image upscaleBlocks(const Image& samples, int stride, int width, int height);

}  // namespace rayview
