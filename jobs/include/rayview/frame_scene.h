#pragma once
// One scene's run of frames, the same in one process (jobs/frames_render.cpp) and under MPI (cluster/cluster_frames.cpp):
// the geometry built once, each turntable frame's tracer, the frame's file written whole, the progress line.

#include <chrono>
#include <cstddef>
#include <filesystem>
#include <memory>

#include "rayview/frame_plan.h"
#include "rayview/image.h"
#include "rayview/lean_memory.h"
#include "rayview/prepared_scene.h"
#include "rayview/render_settings.h"
#include "rayview/scene.h"
#include "rayview/tracer.h"

namespace rayview {

// What one frame renders from: its parameters (the turned camera) and the tracer that reads them.
struct FrameTracer {
  FrameTracer(SceneParameters frameParameters, const PreparedGeometry& geometry, const RenderSettings& settings)
      : parameters(std::move(frameParameters)), tracer(parameters, geometry, settings) {}
  FrameTracer(const FrameTracer&) = delete;  // the tracer keeps a reference to `parameters`
  FrameTracer& operator=(const FrameTracer&) = delete;

  const SceneParameters parameters;
  const Tracer tracer;
};

// A scene whose frames are rendered: its geometry and the turntable's pivot, computed once.
class FrameScene {
 public:
  // `settings` carry the command line's knobs; a back-end that cannot be built falls back to the reference BVH,
  // as for `rayview render`.
  FrameScene(std::shared_ptr<const Scene> scene, RenderSettings settings, BvhBuild build);

  const Scene& scene() const { return *scene_; }
  // Frame `frame` of a turntable of `frames` (frames 0: the scene's own camera).
  std::unique_ptr<FrameTracer> frame(int frame, int frames) const;

 private:
  std::shared_ptr<const Scene> scene_;
  RenderSettings settings_;
  std::shared_ptr<const PreparedGeometry> geometry_;
  glm::dvec3 pivot_{0.0};
};

// The memory layout of the job's images of `scene` (--memory: lean when asked, or when the fast layout's estimated
// peak would not fit), as every driver builds them: the same images either way.
MemoryPlan memoryPlanFor(const RenderJob& job, const Scene& scene);

// Opens the scene of `frame` (its camera) as `job` says, printing its warnings unless quiet. Returns kExitOk, or the
// exit code with the message printed.
int openFrameScene(const RenderJob& job, const FrameJob& frame, LoadedScene& loaded);

// Writes a frame whole, its directory made first. Returns kExitOk, or kExitIoFailure with the message printed.
int writeFrameFile(const std::filesystem::path& path, Image image);

// The line after each frame: "frame 12 of 360 written (spin_0011.png); 348 remaining, about 410 s left".
class FrameProgress {
 public:
  explicit FrameProgress(std::size_t total) : total_(total) {}
  void frameWritten(const std::filesystem::path& output, bool quiet);
  std::size_t written() const { return done_; }
  double seconds() const;

 private:
  std::size_t total_ = 0, done_ = 0;
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
};

}  // namespace rayview
