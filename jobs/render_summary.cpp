#include "render_summary.h"

#include <cstdio>
#include <filesystem>

#include "rayview/diagnostics.h"

namespace rayview {

std::string describeScene(const std::string& scenePath, const Scene& scene) {
  std::string lights;
  scene.lights.forEachType([&](const auto& list) {
    lights += ", " + counted(list.size(), std::string(LightOf<decltype(list)>::kType.noun));
  });
  return (scenePath.empty() ? std::string("default (embedded)") : scenePath) + ": " +
         counted(scene.triangles.size(), "triangle") + lights + ", " + std::to_string(scene.camera.width) + "x" +
         std::to_string(scene.camera.height);
}

std::string describeMemory(const StagePeaks& peaks, std::size_t triangles) {
  if (peaks.write == 0) return "not reported here (no /proc/self/status)";
  auto mib = [](std::uint64_t bytes) { return static_cast<double>(bytes) / (1024.0 * 1024.0); };
  char line[256];
  int at = std::snprintf(line, sizeof line, "peak %.1f MiB", mib(peaks.write));
  if (triangles > 0)
    at += std::snprintf(line + at, sizeof line - static_cast<std::size_t>(at), ", %.0f B/triangle",
                        static_cast<double>(peaks.write) / static_cast<double>(triangles));
  std::snprintf(line + at, sizeof line - static_cast<std::size_t>(at),
                "; peak after load %.1f, BVH build %.1f, render %.1f, write %.1f MiB", mib(peaks.load),
                mib(peaks.build), mib(peaks.render), mib(peaks.write));
  return line;
}

void printRenderSummary(const RenderSummary& s) {
  std::printf("scene      %s\n", s.sceneLine.c_str());
  std::printf("settings   %s\n", s.settingsLine.c_str());
  std::printf("time       load %.1f ms, BVH build %.1f ms, render %.1f ms, write %.1f ms\n", s.loadMs, s.buildMs,
              s.renderMs, s.writeMs);
  std::printf("start-up   %.1f ms: main() to the first ray, less load and BVH build\n", s.startupMs);
  std::printf("rays       camera %llu, shadow %llu, reflection %llu, total %llu, %.2f Mrays/s\n",
              static_cast<unsigned long long>(s.rays.camera), static_cast<unsigned long long>(s.rays.shadow),
              static_cast<unsigned long long>(s.rays.reflection), static_cast<unsigned long long>(s.rays.total()),
              s.megaRaysPerSecond);
  std::printf("memory     %s\n", describeMemory(s.peaks, s.triangles).c_str());
  std::printf("wrote      %s\n", std::filesystem::absolute(s.outputPath).c_str());
}

}  // namespace rayview
