#pragma once
// Rendering a whole image on the thread pool, tile by tile, centre first. Deterministic: every pixel is a
// function of the scene and settings only, so the image is bit-identical for any thread count.

#include <atomic>
#include <cstdint>

#include "rayview/deflated_image.h"
#include "rayview/image.h"
#include "rayview/thread_pool.h"
#include "rayview/tracer.h"

namespace rayview {

struct FrameStats {
  double renderMs = 0.0;
  RayCounts rays;
  double megaRaysPerSecond() const { return renderMs > 0.0 ? rays.total() / (renderMs * 1000.0) : 0.0; }
};

// Renders into `image` (resized to the camera's resolution). Returns false when `stop` was raised before the
// image was complete; the image is then partial and must not be shown or written.
bool renderFrame(const Tracer& tracer, int width, int height, ThreadPool& pool, Image& image, FrameStats& stats,
                 const std::atomic<bool>* stop = nullptr);

// The same image, rendered in bands of rows and kept deflated (lean_memory.h): the pixels are renderFrame's, bit for
// bit, but the whole image is never held. Throws std::bad_alloc.
void renderFrameDeflated(const Tracer& tracer, int width, int height, ThreadPool& pool, DeflatedImage& image,
                         FrameStats& stats);

}  // namespace rayview
