#include "frames_command.h"

#include <chrono>
#include <cstdio>
#include <memory>
#include <system_error>

#include "frame_plan.h"
#include "rayview/frame_renderer.h"
#include "rayview/prepared_scene.h"
#include "rayview/scene_bounds.h"
#include "rayview/scene_source.h"

namespace rayview {
namespace {

using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

}  // namespace

int pendingFrames(const CommandLine& command, std::vector<FrameJob>& pending, std::size_t& asked) {
  std::vector<FrameJob> jobs;
  try {
    jobs = planFrames(command);
  } catch (const UsageError& error) {
    std::fprintf(stderr, "rayview: error: %s\n", error.what());
    return kExitBadInput;
  }
  asked = jobs.size();
  for (FrameJob& job : jobs) {
    if (const std::string problem = renderOutputProblem(job.output, job.scenePath); !problem.empty()) {
      std::fprintf(stderr, "rayview: error: %s\n", problem.c_str());
      return kExitBadInput;
    }
    if (command.overwrite || !frameFileComplete(job.output)) pending.push_back(std::move(job));
  }
  return kExitOk;
}

namespace {

struct Progress {
  std::size_t total = 0, done = 0;
  Clock::time_point start = Clock::now();

  void frameWritten(const FrameJob& job, bool quiet) {
    ++done;
    if (quiet) return;
    const double elapsed = secondsSince(start);
    const std::size_t left = total - done;
    std::fprintf(stderr, "rayview: frame %zu of %zu written (%s); %zu remaining, about %.0f s left\n", done, total,
                 job.output.filename().c_str(), left, elapsed / static_cast<double>(done) * static_cast<double>(left));
  }
};

// The frames of one scene (consecutive in `pending` from `first`): loaded and built once. Returns the exit code.
int renderSceneFrames(const CommandLine& command, const std::vector<FrameJob>& pending, std::size_t& next,
                      Progress& progress) {
  const std::string& scenePath = pending[next].scenePath;
  LoadedScene loaded;
  try {
    LoadOptions options;
    options.strict = command.strict;
    loaded = loadSceneOrDefault(scenePath, options);
  } catch (const SceneError& error) {
    std::fprintf(stderr, "%s\n", error.what());
    return kExitBadInput;
  }
  if (!command.quiet)
    for (const Diagnostic& warning : loaded.warnings) std::fprintf(stderr, "%s\n", warning.format().c_str());
  RenderSettings settings;
  applyKnobs(command.knobs, {&loaded.scene.parameters(), &settings});
  const auto scene = std::make_shared<const Scene>(std::move(loaded.scene));
  const auto geometry = prepareGeometry(scene, settings.accel, BvhLayout::Fast);
  if (!geometry->accelFallback.empty()) settings.accel = AccelKind::Reference;
  const glm::dvec3 pivot = orbitPivot(scene->camera, sceneBounds(*scene));
  ThreadPool pool(command.threads);
  for (; next < pending.size() && pending[next].scenePath == scenePath; ++next) {
    const FrameJob& job = pending[next];
    SceneParameters parameters = scene->parameters();
    parameters.camera = turntableCamera(scene->camera, pivot, job.frame, job.frames);
    const Tracer tracer(parameters, *geometry, settings);
    Image image;
    FrameStats stats;
    renderFrame(tracer, parameters.camera.width, parameters.camera.height, pool, image, stats);
    try {
      std::error_code ignored;
      if (job.output.has_parent_path()) std::filesystem::create_directories(job.output.parent_path(), ignored);
      writeImageFile(job.output, std::move(image));
    } catch (const ImageIoError& error) {
      std::fprintf(stderr, "rayview: error: %s\n", error.what());
      return kExitIoFailure;
    }
    progress.frameWritten(job, command.quiet);
  }
  return kExitOk;
}

}  // namespace

int runFramesCommand(const CommandLine& command) {
  std::vector<FrameJob> pending;
  std::size_t asked = 0;
  if (const int code = pendingFrames(command, pending, asked); code != kExitOk) return code;
  if (!command.quiet)
    std::printf("frames     %zu asked, %zu complete already, %zu to render\n", asked, asked - pending.size(),
                pending.size());
  Progress progress;
  progress.total = pending.size();
  for (std::size_t next = 0; next < pending.size();)
    if (const int code = renderSceneFrames(command, pending, next, progress); code != kExitOk) return code;
  if (!command.quiet) std::printf("time       %.1f s for %zu frames\n", secondsSince(progress.start), pending.size());
  return kExitOk;
}

}  // namespace rayview
