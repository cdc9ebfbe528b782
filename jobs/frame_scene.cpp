#include "rayview/frame_scene.h"

#include <cstdio>
#include <system_error>

#include "rayview/exit_codes.h"
#include "rayview/scene_source.h"
#include "rayview/scene_bounds.h"

namespace rayview {

FrameScene::FrameScene(std::shared_ptr<const Scene> scene, RenderSettings settings, BvhBuild build)
    : scene_(std::move(scene)), settings_(settings) {
  geometry_ = prepareGeometry(scene_, settings_.accel, build);
  if (!geometry_->accelFallback.empty()) settings_.accel = AccelKind::Reference;
  pivot_ = orbitPivot(scene_->camera, sceneBounds(*scene_));
}

std::unique_ptr<FrameTracer> FrameScene::frame(int frame, int frames) const {
  SceneParameters parameters = scene_->parameters();
  parameters.camera = turntableCamera(scene_->camera, pivot_, frame, frames);
  return std::make_unique<FrameTracer>(std::move(parameters), *geometry_, settings_);
}

MemoryPlan memoryPlanFor(const RenderJob& job, const Scene& scene) {
  const std::size_t pixels = static_cast<std::size_t>(std::max(scene.camera.width, 0)) *
                             static_cast<std::size_t>(std::max(scene.camera.height, 0));
  return planMemory(job.open.memory, scene.triangles.size(), pixels, availableMemoryBytes());
}

int openFrameScene(const RenderJob& job, const FrameJob& frame, LoadedScene& loaded) {
  try {
    loaded = openScene(frame.scenePath, jobForFrame(job, frame).open, nullptr, job.threads);
  } catch (const SceneError& error) {
    std::fprintf(stderr, "%s\n", error.what());
    return kExitBadInput;
  }
  if (!job.quiet)
    for (const Diagnostic& warning : loaded.warnings) std::fprintf(stderr, "%s\n", warning.format().c_str());
  return kExitOk;
}

int writeFrameFile(const std::filesystem::path& path, Image image) {
  try {
    std::error_code ignored;  // a directory that cannot be made fails the write, which says so
    if (path.has_parent_path()) std::filesystem::create_directories(path.parent_path(), ignored);
    writeImageFile(path, std::move(image));
  } catch (const ImageIoError& error) {
    std::fprintf(stderr, "rayview: error: %s\n", error.what());
    return kExitIoFailure;
  }
  return kExitOk;
}

double FrameProgress::seconds() const {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
}

void FrameProgress::frameWritten(const std::filesystem::path& output, bool quiet) {
  ++done_;
  if (quiet) return;
  const std::size_t left = total_ - done_;
  std::fprintf(stderr, "rayview: frame %zu of %zu written (%s); %zu remaining, about %.0f s left\n", done_, total_,
               output.filename().c_str(), left, seconds() / static_cast<double>(done_) * static_cast<double>(left));
}

}  // namespace rayview
