#include "single_render.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <utility>

#include "rayview/exit_codes.h"
#include "rayview/process_start.h"
#include "rayview/accel.h"
#include "rayview/deflated_image.h"
#include "rayview/frame_renderer.h"
#include "rayview/frame_scene.h"
#include "rayview/lean_memory.h"
#include "rayview/prepared_scene.h"
#include "rayview/process_memory.h"
#include "rayview/scene_open.h"
#include "rayview/scene_source.h"
#include "render_summary.h"

namespace rayview {
namespace {

using Clock = std::chrono::steady_clock;

double msSince(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

// One `rayview render`, as the stages it runs in order; a stage that ends the command returns its exit status.
class RenderRun {
 public:
  explicit RenderRun(const RenderJob& job) : job_(job), output_(job.output), settings_(renderSettingsOf(job)) {
    summary_.outputPath = job.output.string();
  }

  std::optional<int> checkOutput();
  std::optional<int> load();
  std::optional<int> render();
  std::optional<int> write();
  void report() const {
    if (!job_.quiet) printRenderSummary(summary_);
  }

 private:
  std::uint64_t peakNow() const { return job_.quiet ? 0 : processMemory().peak; }
  std::optional<int> fail(int status, const std::string& message) const {
    std::fprintf(stderr, "%s\n", message.c_str());
    return status;
  }
  std::string sceneName() const { return job_.scene().empty() ? "default scene" : job_.scene(); }
  void trace(const Scene& scene, const PreparedGeometry& geometry);

  const RenderJob& job_;
  const std::filesystem::path output_;
  LoadedScene loaded_;
  RenderSettings settings_;
  MemoryPlan memory_;
  Image image_;
  DeflatedImage deflated_;
  RenderSummary summary_;
};

std::optional<int> RenderRun::checkOutput() {
  if (const std::string problem = renderOutputProblem(output_, job_.scene()); !problem.empty())
    return fail(kExitBadInput, "rayview: error: " + problem);
  return std::nullopt;
}

std::optional<int> RenderRun::load() {
  const auto start = Clock::now();
  try {
    loaded_ = openScene(job_.scene(), job_.open, nullptr, job_.threads);
  } catch (const SceneError& error) {
    return fail(kExitBadInput, error.what());
  }
  summary_.loadMs = msSince(start);
  summary_.peaks.load = peakNow();
  if (const std::string problem = outputOverwritesInput(output_, job_.scene(), &loaded_.scene); !problem.empty())
    return fail(kExitBadInput, "rayview: error: " + problem);
  if (!job_.quiet)
    for (const Diagnostic& warning : loaded_.warnings) std::fprintf(stderr, "%s\n", warning.format().c_str());
  // The knobs given on the command line, written once into their homes: the settings and the scene's parameters.
  applyKnobs(job_.knobs, {&loaded_.scene.parameters(), &settings_});
  memory_ = memoryPlanFor(job_, loaded_.scene);
  return std::nullopt;
}

// The scene, its BVH and the render threads live only in this stage: they are released before the image is
// written, so the write's own memory comes in their place instead of on top of them.
std::optional<int> RenderRun::render() {
  // Shared, not copied: the geometry is the largest thing a big scene holds.
  const auto shared = std::make_shared<const Scene>(std::move(loaded_.scene));
  const std::shared_ptr<const PreparedGeometry> geometry =
      prepareGeometry(shared, settings_.accel, memory_.lean ? BvhBuild::Lean : BvhBuild::OneImage);
  if (!geometry->accelFallback.empty()) {
    std::fprintf(stderr, "%s: warning: %s; rendering with the reference BVH instead\n", sceneName().c_str(),
                 geometry->accelFallback.c_str());
    settings_.accel = AccelKind::Reference;
  }
  summary_.buildMs = geometry->buildMs;
  summary_.peaks.build = std::max(summary_.peaks.load, peakNow());
  trace(*shared, *geometry);
  summary_.peaks.render = std::max(summary_.peaks.build, peakNow());
  return std::nullopt;
}

void RenderRun::trace(const Scene& scene, const PreparedGeometry& geometry) {
  ThreadPool pool(job_.threads);
  const Tracer tracer(scene.parameters(), geometry, settings_);
  summary_.startupMs = msSinceProcessStart() - summary_.loadMs - summary_.buildMs;
  FrameStats stats;
  if (memory_.lean)
    renderFrameDeflated(tracer, scene.camera.width, scene.camera.height, pool, deflated_, stats);
  else
    renderFrame(tracer, scene.camera.width, scene.camera.height, pool, image_, stats);
  summary_.renderMs = stats.renderMs;
  summary_.rays = stats.rays;
  summary_.megaRaysPerSecond = stats.megaRaysPerSecond();
  summary_.triangles = scene.triangles.size();
  summary_.sceneLine = describeScene(job_.scene(), scene);
  SceneParameters parameters = scene.parameters();
  parameters.maxRayDepth = tracer.maxDepth();
  // The traversal as built: Embree asked for a small scene builds the packet BVH.
  RenderSettings built = settings_;
  built.accel = geometry.accel->kind();
  summary_.settingsLine = describeKnobValues(parameters, built);
  if (built.accel != settings_.accel)
    summary_.settingsLine += " (" + std::string(toString(settings_.accel)) + " asked for)";
  summary_.settingsLine += "; memory " + std::string(memory_.lean ? "lean" : "fast") + " (" + memory_.reason +
                           "); " + counted(static_cast<std::size_t>(pool.size()), "thread");
}

std::optional<int> RenderRun::write() {
  const auto start = Clock::now();
  try {
    if (memory_.lean) {
      image_ = deflated_.inflate();
      deflated_ = {};
    }
    writeImageFile(output_, std::move(image_));
  } catch (const ImageIoError& error) {
    return fail(kExitIoFailure, std::string("rayview: error: ") + error.what());
  }
  summary_.writeMs = msSince(start);
  summary_.peaks.write = std::max(summary_.peaks.render, peakNow());
  return std::nullopt;
}

}  // namespace

int runSingleRender(const RenderJob& job) {
  RenderRun run(job);
  for (auto stage : {&RenderRun::checkOutput, &RenderRun::load, &RenderRun::render, &RenderRun::write})
    if (const std::optional<int> status = (run.*stage)()) return *status;
  run.report();
  return kExitOk;
}

}  // namespace rayview
