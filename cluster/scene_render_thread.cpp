#include "scene_render_thread.h"

#include <exception>
#include <new>

#include "rayview/frame_scene.h"
#include "rayview/frame_renderer.h"
#include "scene_hash.h"

namespace rayview::cluster {

SceneRenderThread::SceneRenderThread(ThreadPool& pool) : pool_(pool), thread_([this] { loop(); }) {}

SceneRenderThread::~SceneRenderThread() {
  {
    std::lock_guard lock(mutex_);
    quit_ = true;
  }
  changed_.notify_all();
  thread_.join();
}

void SceneRenderThread::start(SceneJob job) {
  {
    std::lock_guard lock(mutex_);
    job_ = std::move(job);
  }
  changed_.notify_all();
}

std::optional<SceneFrameDone> SceneRenderThread::next(std::chrono::milliseconds wait) {
  std::unique_lock lock(mutex_);
  if (!changed_.wait_for(lock, wait, [this] { return !finished_.empty(); })) return std::nullopt;
  SceneFrameDone done = std::move(finished_.front());
  finished_.pop_front();
  return done;
}

void SceneRenderThread::post(SceneFrameDone done) {
  {
    std::lock_guard lock(mutex_);
    finished_.push_back(std::move(done));
  }
  changed_.notify_all();
}

void SceneRenderThread::loop() {
  std::unique_lock lock(mutex_);
  for (;;) {
    changed_.wait(lock, [this] { return quit_ || job_.has_value(); });
    if (quit_) return;
    const SceneJob job = std::move(*job_);
    job_.reset();
    lock.unlock();
    render(job);
    lock.lock();
  }
}

// The single process's run of frames (frames_command.cpp): the scene built once, each frame by renderFrame.
void SceneRenderThread::render(const SceneJob& job) {
  using Clock = std::chrono::steady_clock;
  auto start = Clock::now();
  std::unique_ptr<FrameScene> scene;
  std::uint64_t hash = 0;
  try {
    SceneToRender obtained = job.obtain();
    if (job.hash) hash = sceneHash(*obtained.scene);
    scene = std::make_unique<FrameScene>(std::move(obtained.scene), obtained.settings, BvhBuild::OneImage);
  } catch (const std::exception& error) {
    post({job.run, 0, Image(), 0.0, RayCounts(), 0, error.what()});
    return;
  }
  for (std::size_t k = 0; k + 1 < job.frames.size(); k += 2) {
    SceneFrameDone done{job.run, static_cast<std::int32_t>(k / 2), Image(), 0.0, RayCounts(), hash, {}};
    try {
      const auto frame = scene->frame(job.frames[k], job.frames[k + 1]);
      FrameStats stats;
      renderFrame(frame->tracer, frame->parameters.camera.width, frame->parameters.camera.height, pool_, done.image,
                  stats);
      done.rays = stats.rays;
    } catch (const std::bad_alloc&) {
      post({job.run, done.frame, Image(), 0.0, RayCounts(), 0, "rayview: error: out of memory rendering the scene"});
      return;
    }
    done.busyMs = std::chrono::duration<double, std::milli>(Clock::now() - start).count();
    start = Clock::now();
    post(std::move(done));
  }
}

}  // namespace rayview::cluster
