#include "file_image_task.h"

#include <algorithm>
#include <chrono>
#include <new>
#include <string>

#include "rayview/grid_render.h"

namespace rayview {

FileImageTask::FileImageTask(int threads)
    : threads_(threads),
      worker_([this](std::uint64_t id, const std::shared_ptr<const PixelSource>& source, const std::atomic<bool>& cancel) {
        return run(id, source, cancel);
      }) {}

std::uint64_t FileImageTask::start(std::shared_ptr<const PixelSource> source) {
  return worker_.submit(std::move(source));
}

double FileImageTask::progress() const {
  const std::int64_t planned = pixelsPlanned_.load(std::memory_order_relaxed);
  if (planned <= 0) return 0.0;
  return std::min(1.0, static_cast<double>(pixelsDone_.load(std::memory_order_relaxed)) / static_cast<double>(planned));
}

FileImageResult FileImageTask::run(std::uint64_t id, const std::shared_ptr<const PixelSource>& source,
                                   const std::atomic<bool>& cancel) {
  FileImageResult result;
  result.id = id;
  try {
    render(result, source, cancel);
  } catch (const std::bad_alloc&) {
    // The save reports it (its failure line), and the viewer goes on.
    result.image = Image();
    result.cancelled = true;
    result.error = "out of memory rendering the file's image (" + std::to_string(source->width()) + "x" +
                   std::to_string(source->height()) + ")";
  }
  return result;
}

void FileImageTask::render(FileImageResult& result, const std::shared_ptr<const PixelSource>& source,
                                      const std::atomic<bool>& cancel) {
  if (!pool_) pool_ = std::make_unique<ThreadPool>(threads_);
  const auto start = std::chrono::steady_clock::now();
  result.image = Image(source->width(), source->height());
  pixelsDone_.store(0);
  pixelsPlanned_.store(static_cast<std::int64_t>(source->width()) * source->height());
  RayCounts rays;
  // The same pixels as `rayview render` (PixelSource::pixel is the headless render's tracePixel).
  const bool complete = renderGrid(
      [&](const PixelXY* pixels, int count, Color* out, RayCounts& counts) {
        source->pixels(pixels, count, out, counts);
        pixelsDone_.fetch_add(count, std::memory_order_relaxed);
      },
      1, 0, *pool_, result.image, rays, [&] { return cancel.load(std::memory_order_relaxed); }, source->quantization());
  result.cancelled = !complete;
  if (!complete) result.image = Image();
  result.renderMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();

}

}  // namespace rayview
