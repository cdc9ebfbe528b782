#include "frames_command.h"

#include <cstdio>
#include <memory>

#include "frame_plan.h"
#include "frame_scene.h"
#include "rayview/frame_renderer.h"
#include "rayview/scene_source.h"

namespace rayview {

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

// The frames of one scene (consecutive in `pending` from `next`): loaded and built once. Returns the exit code.
int renderSceneFrames(const CommandLine& command, const std::vector<FrameJob>& pending, std::size_t& next,
                      FrameProgress& progress) {
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
  const FrameScene scene(std::make_shared<const Scene>(std::move(loaded.scene)), settings);
  ThreadPool pool(command.threads);
  for (; next < pending.size() && pending[next].scenePath == scenePath; ++next) {
    const FrameJob& job = pending[next];
    const auto frame = scene.frame(job.frame, job.frames);
    Image image;
    FrameStats stats;
    renderFrame(frame->tracer, frame->parameters.camera.width, frame->parameters.camera.height, pool, image, stats);
    if (const int code = writeFrameFile(job.output, std::move(image)); code != kExitOk) return code;
    progress.frameWritten(job.output, command.quiet);
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
  FrameProgress progress(pending.size());
  for (std::size_t next = 0; next < pending.size();)
    if (const int code = renderSceneFrames(command, pending, next, progress); code != kExitOk) return code;
  if (!command.quiet) std::printf("time       %.1f s for %zu frames\n", progress.seconds(), pending.size());
  return kExitOk;
}

}  // namespace rayview
