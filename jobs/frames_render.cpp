// The frames driver: a turntable, a batch of scenes, or a CENG477 file's cameras, in this process.
#include <cstdio>
#include <memory>

#include "rayview/exit_codes.h"
#include "rayview/frame_plan.h"
#include "rayview/frame_renderer.h"
#include "rayview/frame_scene.h"
#include "rayview/scene_source.h"
#include "single_render.h"

namespace rayview {
namespace {

// The frames of one scene and camera (consecutive in `pending` from `next`): opened and built once. Returns the exit
// code.
int renderSceneFrames(const RenderJob& job, const std::vector<FrameJob>& pending, std::size_t& next,
                      FrameProgress& progress) {
  const FrameJob& first = pending[next];
  LoadedScene loaded;
  if (const int code = openFrameScene(job, first, loaded); code != kExitOk) return code;
  RenderSettings settings = renderSettingsOf(job);
  applyKnobs(job.knobs, {&loaded.scene.parameters(), &settings});
  const BvhBuild build = memoryPlanFor(job, loaded.scene).lean ? BvhBuild::Lean : BvhBuild::OneImage;
  const FrameScene scene(std::make_shared<const Scene>(std::move(loaded.scene)), settings, build);
  // What the opening read (a texture, a model's files) is known only now: no frame of the scene is written over it.
  for (std::size_t k = next; k < pending.size() && sameSceneAndCamera(pending[k], first); ++k)
    if (const std::string problem = outputOverwritesInput(pending[k].output, first.scenePath, &scene.scene());
        !problem.empty()) {
      std::fprintf(stderr, "rayview: error: %s\n", problem.c_str());
      return kExitBadInput;
    }
  ThreadPool pool(job.threads);
  for (; next < pending.size() && sameSceneAndCamera(pending[next], first); ++next) {
    const FrameJob& frameJob = pending[next];
    const auto frame = scene.frame(frameJob.frame, frameJob.frames);
    Image image;
    FrameStats stats;
    renderFrame(frame->tracer, frame->parameters.camera.width, frame->parameters.camera.height, pool, image, stats);
    if (const int code = writeFrameFile(frameJob.output, std::move(image)); code != kExitOk) return code;
    progress.frameWritten(frameJob.output, job.quiet);
  }
  return kExitOk;
}

}  // namespace

int runFramesJob(const RenderJob& job) {
  std::vector<FrameJob> pending;
  std::size_t asked = 0;
  if (const int code = pendingFrames(job, pending, asked); code != kExitOk) return code;
  if (!job.quiet)
    std::printf("frames     %zu asked, %zu complete already, %zu to render\n", asked, asked - pending.size(),
                pending.size());
  FrameProgress progress(pending.size());
  for (std::size_t next = 0; next < pending.size();)
    if (const int code = renderSceneFrames(job, pending, next, progress); code != kExitOk) return code;
  if (!job.quiet) std::printf("time       %.1f s for %zu frames\n", progress.seconds(), pending.size());
  return kExitOk;
}

}  // namespace rayview
