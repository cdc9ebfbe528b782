#pragma once
// One scene's frames rendered on a thread of its own (a batch dealt by scene, docs/scale-out.md "Frames"), so that
// the thread that calls MPI stays free to answer: rank 0's own share of the scenes, and a worker's.

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "rayview/image.h"
#include "rayview/render_settings.h"
#include "rayview/scene.h"
#include "rayview/thread_pool.h"
#include "rayview/tracer.h"

namespace rayview::cluster {

struct SceneToRender {
  std::shared_ptr<const Scene> scene;
  RenderSettings settings;
};

struct SceneJob {
  std::int32_t run = 0;
  // Gives the scene (decoding it on a worker, on this thread); throws std::exception with the reason.
  std::function<SceneToRender()> obtain;
  std::vector<std::int32_t> frames;  // pairs: turntable frame, frames
  bool hash = false;                 // compute the scene's hash (a worker: rank 0 compares it with its own)
};

// A frame finished, or the reason the scene could not be rendered (`error` set, no image).
struct SceneFrameDone {
  std::int32_t run = 0;
  std::int32_t frame = 0;  // index into the job's frames
  Image image;
  double busyMs = 0.0;  // the frame's render; the first frame also carries obtaining and building the scene
  RayCounts rays;
  std::uint64_t hash = 0;
  std::string error;
};

class SceneRenderThread {
 public:
  explicit SceneRenderThread(ThreadPool& pool);
  ~SceneRenderThread();
  SceneRenderThread(const SceneRenderThread&) = delete;
  SceneRenderThread& operator=(const SceneRenderThread&) = delete;

  void start(SceneJob job);
  // The next finished frame (or error), waiting up to `wait` for one.
  std::optional<SceneFrameDone> next(std::chrono::milliseconds wait);

 private:
  void loop();
  void render(const SceneJob& job);
  void post(SceneFrameDone done);

  ThreadPool& pool_;
  std::mutex mutex_;
  std::condition_variable changed_;
  std::optional<SceneJob> job_;
  bool quit_ = false;
  std::deque<SceneFrameDone> finished_;
  std::thread thread_;  // last: starts once the members it uses exist
};

}  // namespace rayview::cluster
