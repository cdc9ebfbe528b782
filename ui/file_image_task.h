#pragma once
// The file's image rendered off the UI thread, for saving while the window view shows another resolution
// (Ctrl+S saves the file's resolution, equal to `rayview render`, never a coarse pass). One
// persistent worker thread (RequestWorker) renders the whole image on a thread pool of its own (made at the
// first request, then kept); a new request supersedes the running one. No GL here.

#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>

#include "rayview/image.h"
#include "rayview/pixel_source.h"
#include "rayview/thread_pool.h"
#include "request_worker.h"

namespace rayview {

struct FileImageResult {
  std::uint64_t id = 0;
  bool cancelled = false;
  Image image;  // the source's whole image, when not cancelled
  double renderMs = 0.0;
  std::string error;  // why there is no image when the render failed (out of memory); "" otherwise
};

class FileImageTask {
 public:
  explicit FileImageTask(int threads);  // of the pool; <= 0: one per hardware thread

  // Called on the worker when a result is ready (the viewer wakes its UI loop). Set it before start().
  void setFinishedListener(std::function<void()> listener) { worker_.setFinishedListener(std::move(listener)); }
  // Returns at once with the request's id; a render still running stops within a tile.
  std::uint64_t start(std::shared_ptr<const PixelSource> source);
  void cancel() { worker_.cancel(); }
  std::optional<FileImageResult> takeResult() { return worker_.take(); }
  bool busy() const { return worker_.busy(); }
  // The share of the running render's pixels done, 0 to 1.
  double progress() const;

 private:
  FileImageResult run(std::uint64_t id, const std::shared_ptr<const PixelSource>& source, const std::atomic<bool>& cancel);
  void render(FileImageResult& result, const std::shared_ptr<const PixelSource>& source, const std::atomic<bool>& cancel);

  const int threads_;
  std::unique_ptr<ThreadPool> pool_;  // made by the worker at its first request, then kept
  std::atomic<std::int64_t> pixelsDone_{0};
  std::atomic<std::int64_t> pixelsPlanned_{0};
  RequestWorker<std::shared_ptr<const PixelSource>, FileImageResult> worker_;  // last: its thread uses the above
};

}  // namespace rayview
