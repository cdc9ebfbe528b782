#include "render_command.h"

#include <chrono>
#include <cstdio>
#include <filesystem>

#include "rayview/camera_rays.h"
#include "rayview/frame_renderer.h"
#include "rayview/prepared_scene.h"
#include "rayview/scene_source.h"

namespace rayview {
namespace {

double msSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

int runRenderCommand(const CommandLine& command) {
  const std::filesystem::path output = command.outputPath;
  if (!isSupportedImageExtension(output)) {
    std::fprintf(stderr, "rayview: error: the output must end in .png or .ppm: %s\n", command.outputPath.c_str());
    return kExitBadInput;
  }

  const auto loadStart = std::chrono::steady_clock::now();
  LoadedScene loaded;
  try {
    loaded = loadSceneOrDefault(command.scenePath, LoadOptions{command.strict, true});
  } catch (const SceneError& error) {
    std::fprintf(stderr, "%s\n", error.what());
    return kExitBadInput;
  }
  const double loadMs = msSince(loadStart);
  if (!command.quiet)
    for (const Diagnostic& warning : loaded.warnings) std::fprintf(stderr, "%s\n", warning.format().c_str());

  // The knobs given on the command line, written once into their homes: the settings and the scene's parameters.
  Scene& scene = loaded.scene;
  RenderSettings settings;
  applyKnobs(command.knobs, {&scene.parameters(), &settings});
  std::shared_ptr<const PreparedGeometry> geometry = prepareGeometry(scene, settings.accel);
  ThreadPool pool(command.threads);
  const Tracer tracer(scene, *geometry->accel, geometry->shading, settings);
  Image image;
  FrameStats stats;
  renderFrame(tracer, scene.camera.width, scene.camera.height, pool, image, stats);

  try {
    writeImageFile(output, image);
  } catch (const ImageIoError& error) {
    std::fprintf(stderr, "rayview: error: %s\n", error.what());
    return kExitIoFailure;
  }

  if (!command.quiet) {
    const RenderSettings& s = settings;
    std::printf("scene      %s: %s, %s, %s, %dx%d\n",
                command.scenePath.empty() ? "default (embedded)" : command.scenePath.c_str(),
                counted(scene.triangles.size(), "triangle").c_str(), counted(scene.pointLights.size(), "point light").c_str(),
                counted(scene.triangularLights.size(), "triangular light").c_str(), scene.camera.width,
                scene.camera.height);
    std::printf("settings   depth %d, triangular lights %s (%s), accel %s, %s\n", tracer.maxDepth(),
                std::string(toString(s.triangularLightModel)).c_str(), counted(static_cast<std::size_t>(s.lightSamples), "sample").c_str(),
                std::string(toString(geometry->accel->kind())).c_str(),
                counted(static_cast<std::size_t>(pool.size()), "thread").c_str());
    std::printf("time       load %.1f ms, BVH build %.1f ms, render %.1f ms\n", loadMs, geometry->buildMs, stats.renderMs);
    std::printf("rays       camera %llu, shadow %llu, reflection %llu, total %llu, %.2f Mrays/s\n",
                static_cast<unsigned long long>(stats.rays.camera), static_cast<unsigned long long>(stats.rays.shadow),
                static_cast<unsigned long long>(stats.rays.reflection),
                static_cast<unsigned long long>(stats.rays.total()), stats.megaRaysPerSecond());
    std::printf("wrote      %s\n", std::filesystem::absolute(output).c_str());
  }
  return kExitOk;
}

}  // namespace rayview
