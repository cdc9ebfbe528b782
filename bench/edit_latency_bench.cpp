// Edit-to-first-pass and edit-to-final-pass latency of the progressive renderer (issue 3, item 10).
//
// Each iteration is one edit as the viewer makes it: change a material, take a new scene snapshot, restart.
// Reported per scene: first_ms (edit to the first, coarse pass on screen) and final_ms (edit to the final
// pass), the median over the iterations. Goal: first_ms <= 16 on every scene.
#include <benchmark/benchmark.h>

#include <filesystem>

#include "generated_scenes.h"
#include "rayview/progressive_renderer.h"
#include "rayview/scene_loader.h"

namespace rayview {
namespace {

using Clock = std::chrono::steady_clock;

void measureEditLatency(benchmark::State& state, std::shared_ptr<const Scene> original) {
  auto geometry = prepareGeometry(original, AccelKind::Embree);
  ProgressiveRenderer renderer(2);
  SceneParameters edited = original->parameters();  // as the viewer edits: never the meshes
  // Warm up: lets the renderer pick its first stride for this scene, as it would after the first edit.
  for (int i = 0; i < 3; ++i)
    renderer.waitForFinal(renderer.restart(std::make_shared<TracedImage>(original, geometry, RenderSettings{})),
                          std::chrono::minutes(5));
  std::vector<double> firstMs, finalMs;
  int edit = 0;
  for (auto _ : state) {
    edited.materials[0].diffuse.x = (++edit % 2) ? 0.5f : 0.6f;
    // The edit's own cost on the UI thread (snapshot + tracer set-up) counts toward the latency.
    const auto start = Clock::now();
    auto snapshot = std::make_shared<const SceneParameters>(edited);
    auto source = std::make_shared<TracedImage>(snapshot, geometry, RenderSettings{});
    const double editMs = std::chrono::duration<double, std::milli>(Clock::now() - start).count();
    const auto generation = renderer.restart(std::move(source));
    renderer.waitForFinal(generation, std::chrono::minutes(5));
    ProgressiveFrame frame;
    renderer.takeFrameIfNewer(0, frame);
    firstMs.push_back(editMs + frame.firstPassMsSinceRestart);
    finalMs.push_back(editMs + frame.msSinceRestart);
    state.SetIterationTime(frame.msSinceRestart / 1000.0);
  }
  auto median = [](std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v.empty() ? 0.0 : v[v.size() / 2];
  };
  state.counters["first_ms"] = median(firstMs);
  state.counters["final_ms"] = median(finalMs);
  state.counters["first_stride"] = renderer.firstStride();
  state.counters["triangles"] = static_cast<double>(original->triangles.size());
}

void registerScenes() {
  const std::filesystem::path dir = std::filesystem::path(RAYVIEW_SHARED_DIR) / "conformance" / "ceng477";
  std::vector<std::filesystem::path> files;
  if (std::filesystem::exists(dir))
    for (const auto& entry : std::filesystem::directory_iterator(dir)) {
      const std::string name = entry.path().filename().string();
      if (name.ends_with(".xml") && !name.ends_with(".ceng477.xml")) files.push_back(entry.path());
    }
  std::sort(files.begin(), files.end());
  for (const auto& file : files) {
    auto scene = std::make_shared<const Scene>(loadSceneFile(file).scene);
    benchmark::RegisterBenchmark(("EditLatency/" + file.stem().string()).c_str(), measureEditLatency, scene)
        ->UseManualTime()->Unit(benchmark::kMillisecond)->Iterations(8);
  }
  auto big = std::make_shared<const Scene>(bench::heightfieldScene(1'000'000, 800, 600));
  benchmark::RegisterBenchmark("EditLatency/generated_1M_triangles", measureEditLatency, big)
      ->UseManualTime()->Unit(benchmark::kMillisecond)->Iterations(8);
}

}  // namespace
}  // namespace rayview

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  rayview::registerScenes();
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
