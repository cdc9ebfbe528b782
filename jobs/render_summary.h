#pragma once
// What `rayview render` prints once the image is written: the scene, the settings (every knob of the table, the
// traversal actually built, the memory layout and why, the threads), the stages' times, the start-up, the rays and
// the memory.

#include <cstddef>
#include <cstdint>
#include <string>

#include "rayview/frame_renderer.h"
#include "rayview/scene.h"

namespace rayview {

// The process's peak memory as it stood after each stage; 0 where not read (--quiet).
struct StagePeaks {
  std::uint64_t load = 0, build = 0, render = 0, write = 0;
};

struct RenderSummary {
  std::string sceneLine;     // "bunny.xml: 4968 triangles, 1 point light, 800x800"
  std::string settingsLine;  // "depth 3, tri-light area, ..., accel embree (built: packet BVH), memory fast (...), 2 threads"
  double loadMs = 0.0, buildMs = 0.0, renderMs = 0.0, writeMs = 0.0, startupMs = 0.0;
  RayCounts rays;
  double megaRaysPerSecond = 0.0;
  StagePeaks peaks;
  std::size_t triangles = 0;
  std::string outputPath;
};

// "default (embedded): 12 triangles, 1 point light, 1 triangular light, 640x480".
std::string describeScene(const std::string& scenePath, const Scene& scene);

// The memory line: the peak, per triangle, and the peak after each stage.
std::string describeMemory(const StagePeaks& peaks, std::size_t triangles);

void printRenderSummary(const RenderSummary& summary);

}  // namespace rayview
