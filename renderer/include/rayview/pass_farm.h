#pragma once
// A progressive pass traced by other processes (the ranks of an MPI job, cluster/viewer_farm.cpp). The progressive
// renderer keeps what makes the image (sums of samples, quantizing, publishing) and hands over only the tracing,
// so the passes are the same bit for bit wherever their pixels were traced.

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "rayview/color.h"
#include "rayview/grid_render.h"
#include "rayview/pixel_source.h"
#include "rayview/tracer.h"

namespace rayview {

struct FarmPass {
  std::uint64_t generation = 0;
  int stride = 1;      // the pixels (gx * stride, gy * stride) of the image
  int skipStride = 0;  // except those on this grid (the pass before computed them); 0: none
  int sample = -1;     // -1: whole pixels (PixelSource::pixels); k >= 0: anti-aliasing sample k (samples)
};

// What tracing a pass's pixels means for `source`: whole pixels (sample -1) or anti-aliasing sample k, as
// FarmPass::sample says. Every farm traces through this, so its radiance is the local pass's.
inline PixelBatchFunction farmTrace(const PixelSource& source, int sample) {
  if (sample < 0)
    return [&source](const PixelXY* p, int n, Color* out, RayCounts& c) { source.pixels(p, n, out, c); };
  return [&source, sample](const PixelXY* p, int n, Color* out, RayCounts& c) { source.samples(p, n, sample, out, c); };
}

// Radiance of `count` pixels of the pass (colors[n] for pixels[n]), not yet quantized.
using FarmSink = std::function<void(const PixelXY* pixels, const Color* colors, int count)>;

class PassFarm {
 public:
  virtual ~PassFarm() = default;
  // Whether the farm can trace `source` elsewhere (it ships what the source was made of); the renderer traces
  // any other source itself.
  virtual bool accepts(const PixelSource& source) const = 0;
  // Traces every pixel of `pass` once, calling `sink` on the calling thread as pieces arrive. Returns false when
  // `stopped()` turned true before the pass was complete.
  virtual bool renderPass(const PixelSource& source, const FarmPass& pass, const FarmSink& sink,
                          const std::function<bool()>& stopped, RayCounts& rays) = 0;
  // Who traces, and how much each has, for the viewer's stats ("3 ranks, tiles 120 / 80 / 75"). Any thread.
  virtual std::string describe() const { return {}; }
  // The processes that died or were left out, each with why ("rank 1: fell silent"); empty when none. Any thread.
  virtual std::vector<std::string> lostRanks() const { return {}; }
};

}  // namespace rayview
