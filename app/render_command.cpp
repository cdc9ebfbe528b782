#include "render_command.h"

#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <utility>

#include "lean_heap.h"
#include "process_start.h"
#include "rayview/accel.h"
#include "rayview/camera_rays.h"
#include "rayview/frame_renderer.h"
#include "rayview/lean_memory.h"
#include "rayview/model_client.h"
#include "rayview/prepared_scene.h"
#include "rayview/process_memory.h"
#include "rayview/scene_source.h"

namespace rayview {
namespace {

double msSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

// SIGINT / SIGTERM during a render: remove the image's temporary file if it is being written, exit
// 130 / 143 as a shell would report the signal. The existing output is never touched before the rename.
extern "C" void onInterrupt(int signal) {
  if (const char* temporary = temporaryFileInProgress()) ::unlink(temporary);
  ::_exit(128 + signal);
}

void removeTemporaryOnInterrupt() {
  struct sigaction action {};
  action.sa_handler = onInterrupt;
  sigemptyset(&action.sa_mask);
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
}

// The summary's memory line: the process's peak, per triangle (issue 8 item 4's measure), and the peak as it stood
// after each stage, which says where it was reached.
std::string memoryLine(const std::uint64_t (&peaks)[4], std::size_t triangles) {
  if (peaks[3] == 0) return "not reported here (no /proc/self/status)";
  auto mib = [](std::uint64_t bytes) { return static_cast<double>(bytes) / (1024.0 * 1024.0); };
  char line[256];
  int at = std::snprintf(line, sizeof line, "peak %.1f MiB", mib(peaks[3]));
  if (triangles > 0)
    at += std::snprintf(line + at, sizeof line - static_cast<std::size_t>(at), ", %.0f B/triangle",
                        static_cast<double>(peaks[3]) / static_cast<double>(triangles));
  std::snprintf(line + at, sizeof line - static_cast<std::size_t>(at),
                "; peak after load %.1f, BVH build %.1f, render %.1f, write %.1f MiB", mib(peaks[0]), mib(peaks[1]),
                mib(peaks[2]), mib(peaks[3]));
  return line;
}

std::string sceneName(const CommandLine& command) {
  return command.scenePath.empty() ? std::string("default scene") : command.scenePath;
}

}  // namespace

int runRenderCommand(const CommandLine& command) {
  const std::filesystem::path output = command.outputPath;
  if (!isSupportedImageExtension(output)) {
    std::fprintf(stderr, "rayview: error: the output must end in .png or .ppm: %s\n", command.outputPath.c_str());
    return kExitBadInput;
  }

  if (const std::string problem = outputOverwritesInput(output, command.scenePath, nullptr); !problem.empty()) {
    std::fprintf(stderr, "rayview: error: %s\n", problem.c_str());
    return kExitBadInput;
  }
  const auto loadStart = std::chrono::steady_clock::now();
  LoadedScene loaded;
  try {
    LoadOptions options;
    options.strict = command.strict;
    options.beforeArrays = useLeanHeapForEstimate;
    loaded = isModelFile(command.scenePath) ? loadModelScene(command.scenePath, command.model)
                                            : loadSceneOrDefault(command.scenePath, options);
  } catch (const SceneError& error) {
    std::fprintf(stderr, "%s\n", error.what());
    return kExitBadInput;
  }
  const double loadMs = msSince(loadStart);
  // The memory line's readings, after load, build, render and write: only for a summary that prints them.
  const auto peakNow = [&] { return command.quiet ? std::uint64_t{0} : processMemory().peak; };
  std::uint64_t peaks[4] = {peakNow(), 0, 0, 0};
  if (const std::string problem = outputOverwritesInput(output, command.scenePath, &loaded.scene); !problem.empty()) {
    std::fprintf(stderr, "rayview: error: %s\n", problem.c_str());
    return kExitBadInput;
  }
  removeTemporaryOnInterrupt();
  if (!command.quiet)
    for (const Diagnostic& warning : loaded.warnings) std::fprintf(stderr, "%s\n", warning.format().c_str());

  // The knobs given on the command line, written once into their homes: the settings and the scene's parameters.
  Scene& scene = loaded.scene;
  // A lean scene (rayview/lean_memory.h): its heap lean from here if the loader's estimate did not make it so, and
  // what the load freed given back. Its image is kept deflated while the scene is held.
  const bool lean = isLeanScene(scene.triangles.size());
  if (lean) useLeanHeap();
  RenderSettings settings;
  applyKnobs(command.knobs, {&scene.parameters(), &settings});
  Image image;
  DeflatedImage deflated;
  FrameStats stats;
  std::string sceneLine, settingsLine;
  double buildMs = 0.0, startupMs = 0.0;
  std::size_t triangles = 0;
  // The scene, its BVH and the render threads live only in this block: they are released before the image is
  // written, so the write's own memory (stb_image_write's filtered copy of the image, the PNG) comes in their place
  // instead of on top of them (docs/PERFORMANCE.md, issue 8 item 4).
  {
    // Shared, not copied: the geometry is the largest thing a big scene holds.
    const auto shared = std::make_shared<const Scene>(std::move(scene));
    const Scene& view = *shared;
    // Built for memory: a lean scene gets the packet BVH with bigger leaves; any other, what it would anyway.
    std::shared_ptr<const PreparedGeometry> geometry = prepareGeometry(shared, settings.accel, BuildPriority::Memory);
    if (!geometry->accelFallback.empty()) {
      std::fprintf(stderr, "%s: warning: %s; rendering with the reference BVH instead\n", sceneName(command).c_str(),
                   geometry->accelFallback.c_str());
      settings.accel = AccelKind::Reference;
    }
    peaks[1] = std::max(peaks[0], peakNow());
    ThreadPool pool(command.threads);
    const Tracer tracer(view.parameters(), *geometry, settings);
    // Start-up as issue 8 defines it: process start to the first ray, less load and build.
    startupMs = msSinceProcessStart() - loadMs - geometry->buildMs;
    if (lean)
      renderFrameDeflated(tracer, view.camera.width, view.camera.height, pool, deflated, stats);
    else
      renderFrame(tracer, view.camera.width, view.camera.height, pool, image, stats);
    peaks[2] = std::max(peaks[1], peakNow());
    triangles = view.triangles.size();

    std::string lights;
    view.lights.forEachType([&](const auto& list) {
      lights += ", " + counted(list.size(), std::string(LightOf<decltype(list)>::kType.noun));
    });
    sceneLine = std::string(command.scenePath.empty() ? "default (embedded)" : command.scenePath) + ": " +
                counted(view.triangles.size(), "triangle") + lights + ", " + std::to_string(view.camera.width) + "x" +
                std::to_string(view.camera.height);
    const RenderSettings& s = settings;
    settingsLine = "depth " + std::to_string(tracer.maxDepth()) + ", triangular lights " +
                   std::string(toString(s.triangularLightModel)) + " (" +
                   counted(static_cast<std::size_t>(s.lightSamples), "sample") + "), accel " +
                   std::string(toString(geometry->accel->kind())) + ", " +
                   counted(static_cast<std::size_t>(pool.size()), "thread");
    buildMs = geometry->buildMs;
  }

  const auto writeStart = std::chrono::steady_clock::now();
  try {
    if (lean) {
      useLeanHeapForTheWrite();
      image = deflated.inflate();
      deflated = {};
    }
    writeImageFile(output, std::move(image));
  } catch (const ImageIoError& error) {
    std::fprintf(stderr, "rayview: error: %s\n", error.what());
    return kExitIoFailure;
  }
  const double writeMs = msSince(writeStart);
  peaks[3] = std::max(peaks[2], peakNow());

  if (!command.quiet) {
    std::printf("scene      %s\n", sceneLine.c_str());
    std::printf("settings   %s\n", settingsLine.c_str());
    std::printf("time       load %.1f ms, BVH build %.1f ms, render %.1f ms, write %.1f ms\n", loadMs, buildMs,
                stats.renderMs, writeMs);
    std::printf("start-up   %.1f ms: %s to the first ray, less load and BVH build\n", startupMs,
                processStartIsLaunch() ? "process start" : "main()");
    std::printf("rays       camera %llu, shadow %llu, reflection %llu, total %llu, %.2f Mrays/s\n",
                static_cast<unsigned long long>(stats.rays.camera), static_cast<unsigned long long>(stats.rays.shadow),
                static_cast<unsigned long long>(stats.rays.reflection),
                static_cast<unsigned long long>(stats.rays.total()), stats.megaRaysPerSecond());
    std::printf("memory     %s\n", memoryLine(peaks, triangles).c_str());
    std::printf("wrote      %s\n", std::filesystem::absolute(output).c_str());
  }
  return kExitOk;
}

}  // namespace rayview
