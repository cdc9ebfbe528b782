// Edit-to-first-pass and edit-to-final-pass latency of the progressive renderer, and the
// preview level and latency of each move of a drag: what a viewer user waits for.
//
// EditLatency: each iteration is one edit as the viewer makes it: change a material, take a new scene
// snapshot, restart. Reported per scene: first_ms (edit to the first, coarse pass on screen) and final_ms
// (edit to the final pass), the median over the iterations; headless_ms, the same image rendered as `rayview
// render` does (renderFrame, 2 threads), alternating with the edits, and final_over_headless, the ratio of the
// medians. Goals: first_ms <= 16 on every scene; final_ms at most headless_ms + 10 %, so that interactivity
// costs the final image little (docs/PERFORMANCE.md, "Current figures").
//
// DragLatency: each iteration is one move of a drag as the viewer makes it, after the scene's final pass was
// on screen: the renderer holds one pass per move (setInteractive), the move pans the camera by 1% of the
// near plane's width, takes a snapshot and restarts. Reported: the stride of each move's pass (its preview
// level: the median, finest and coarsest over the moves) and first_ms, from the move to that pass in the
// waiting thread's hands (copied out, as the UI takes it; the texture upload is not in it), median and
// largest. Goal: first_ms <= 16 at every size, and small scenes at full or half resolution. Each scene's
// levels and times, move by move, go to stderr. Scenes: the conformance set and the 1M-triangle scene at their
// size, the project's own scenes (scenes/), and three at 6400x4000.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <condition_variable>
#include <cstdio>
#include <filesystem>
#include <mutex>
#include <string>

#include "generated_scenes.h"
#include "rayview/frame_renderer.h"
#include "rayview/progressive_renderer.h"
#include "rayview/scene_loader.h"

namespace rayview {
namespace {

using Clock = std::chrono::steady_clock;

double msSince(Clock::time_point start) { return std::chrono::duration<double, std::milli>(Clock::now() - start).count(); }

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0.0 : v[v.size() / 2];
}

void measureEditLatency(benchmark::State& state, std::shared_ptr<const Scene> original) {
  auto geometry = prepareGeometry(original, AccelKind::Embree, BvhBuild::Interactive);
  ProgressiveRenderer renderer(2);
  SceneParameters edited = original->parameters();  // as the viewer edits: never the meshes
  // Warm up: lets the renderer pick its first stride for this scene, as it would after the first edit.
  for (int i = 0; i < 3; ++i)
    renderer.waitForFinal(renderer.restart(std::make_shared<TracedImage>(original, geometry, RenderSettings{})),
                          std::chrono::minutes(5));
  std::vector<double> firstMs, finalMs, headlessMs;
  ThreadPool headlessPool(2);
  Image headlessImage;
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
    // The headless render of the same snapshot (the renderer is idle: its final pass is done).
    state.PauseTiming();
    const TracedImage headless(snapshot, geometry, RenderSettings{});
    FrameStats stats;
    renderFrame(headless.tracer(), headless.width(), headless.height(), headlessPool, headlessImage, stats);
    headlessMs.push_back(stats.renderMs);
    state.ResumeTiming();
  }
  state.counters["first_ms"] = median(firstMs);
  state.counters["final_ms"] = median(finalMs);
  state.counters["headless_ms"] = median(headlessMs);
  state.counters["final_over_headless"] = median(finalMs) / median(headlessMs);
  state.counters["first_stride"] = renderer.firstStride();
  state.counters["triangles"] = static_cast<double>(original->triangles.size());
}

// Wakes the waiting thread when the renderer publishes a pass, as glfwPostEmptyEvent wakes the viewer's loop.
class PublishSignal {
 public:
  void notify() {
    {
      std::lock_guard lock(mutex_);
      ++count_;
    }
    changed_.notify_all();
  }
  std::uint64_t count() {
    std::lock_guard lock(mutex_);
    return count_;
  }
  void waitPast(std::uint64_t count) {
    std::unique_lock lock(mutex_);
    changed_.wait_for(lock, std::chrono::seconds(1), [&] { return count_ != count; });
  }

 private:
  std::mutex mutex_;
  std::condition_variable changed_;
  std::uint64_t count_ = 0;
};

// The first pass of `generation`, taken as the UI takes frames: only those newer than `version`, the last
// one taken.
ProgressiveFrame takeFirstPass(const ProgressiveRenderer& renderer, PublishSignal& signal, std::uint64_t generation,
                               std::uint64_t& version) {
  ProgressiveFrame frame;
  for (;;) {
    const std::uint64_t published = signal.count();
    while (renderer.takeFrameIfNewer(version, frame)) {
      version = frame.version;
      if (frame.generation == generation) return frame;
    }
    signal.waitPast(published);
  }
}

void measureDrag(benchmark::State& state, std::shared_ptr<const Scene> original, std::string name) {
  auto geometry = prepareGeometry(original, AccelKind::Embree, BvhBuild::Interactive);
  PublishSignal signal;  // outlives the renderer, which calls it
  ProgressiveRenderer renderer(2);
  renderer.setFrameListener([&signal] { signal.notify(); });
  // The scene as the user first sees it: refined to its final pass.
  renderer.waitForFinal(renderer.restart(std::make_shared<TracedImage>(original, geometry, RenderSettings{})),
                        std::chrono::minutes(10));
  ProgressiveFrame shown;  // the UI took the final pass before the drag; it never copies it again
  renderer.takeFrameIfNewer(0, shown);
  std::uint64_t version = shown.version;
  SceneParameters edited = original->parameters();
  Camera& camera = edited.camera;
  const glm::dvec3 right = glm::normalize(glm::cross(camera.gaze, camera.up));
  const glm::dvec3 step = right * (0.01 * (camera.right - camera.left));
  renderer.setInteractive(true);
  std::vector<double> firstMs, strides;
  std::string moves;
  for (auto _ : state) {
    const auto start = Clock::now();
    camera.position += step;
    auto snapshot = std::make_shared<const SceneParameters>(edited);
    const auto generation = renderer.restart(std::make_shared<TracedImage>(snapshot, geometry, RenderSettings{}));
    const ProgressiveFrame frame = takeFirstPass(renderer, signal, generation, version);
    const double ms = msSince(start);
    firstMs.push_back(ms);
    strides.push_back(frame.stride);
    state.SetIterationTime(ms / 1000.0);
    char move[48];
    std::snprintf(move, sizeof move, " 1/%d:%.1f", frame.stride, ms);
    moves += move;
  }
  renderer.restart(nullptr);
  std::fprintf(stderr, "DragLatency/%s %dx%d, level:ms per move:%s\n", name.c_str(), camera.width, camera.height,
               moves.c_str());
  state.counters["stride"] = median(strides);
  state.counters["stride_finest"] = *std::min_element(strides.begin(), strides.end());
  state.counters["stride_coarsest"] = *std::max_element(strides.begin(), strides.end());
  state.counters["first_ms"] = median(firstMs);
  state.counters["first_ms_max"] = *std::max_element(firstMs.begin(), firstMs.end());
  state.counters["triangles"] = static_cast<double>(original->triangles.size());
}

// `scene` at width x height: the near plane keeps its height and centre and takes the new aspect, so pixels
// stay square.
std::shared_ptr<const Scene> resized(Scene scene, int width, int height) {
  Camera& c = scene.parameters().camera;
  const double centre = 0.5 * (c.left + c.right);
  const double halfWidth = 0.5 * (c.top - c.bottom) * width / height;
  c.left = centre - halfWidth;
  c.right = centre + halfWidth;
  c.width = width;
  c.height = height;
  return std::make_shared<const Scene>(std::move(scene));
}

void registerDrag(const std::string& name, std::shared_ptr<const Scene> scene) {
  benchmark::RegisterBenchmark(("DragLatency/" + name).c_str(), measureDrag, scene, name)
      ->UseManualTime()->Unit(benchmark::kMillisecond)->Iterations(16);
}

// The scene files in `dir`, sorted (the conformance set's .ceng477.xml originals left out).
std::vector<std::filesystem::path> sceneFiles(const std::filesystem::path& dir) {
  std::vector<std::filesystem::path> files;
  if (std::filesystem::exists(dir))
    for (const auto& entry : std::filesystem::directory_iterator(dir)) {
      const std::string name = entry.path().filename().string();
      if (name.ends_with(".xml") && !name.ends_with(".ceng477.xml")) files.push_back(entry.path());
    }
  std::sort(files.begin(), files.end());
  return files;
}

void registerScenes() {
  const std::vector<std::filesystem::path> files =
      sceneFiles(std::filesystem::path(RAYVIEW_SHARED_DIR) / "conformance" / "ceng477");
  std::vector<std::pair<std::string, std::shared_ptr<const Scene>>> scenes;
  for (const auto& file : files)
    scenes.emplace_back(file.stem().string(), std::make_shared<const Scene>(loadSceneFile(file).scene));
  scenes.emplace_back("generated_1M_triangles", std::make_shared<const Scene>(bench::heightfieldScene(1'000'000, 800, 600)));
  for (const auto& [name, scene] : scenes)
    benchmark::RegisterBenchmark(("EditLatency/" + name).c_str(), measureEditLatency, scene)
        ->UseManualTime()->Unit(benchmark::kMillisecond)->Iterations(8);
  for (const auto& [name, scene] : scenes) registerDrag(name, scene);
  // The project's own scenes: small ones, whose full pass fits a frame (a soft shadow under triangular_light's
  // area light is what a user judges while dragging).
  for (const auto& file : sceneFiles(std::filesystem::path(RAYVIEW_SOURCE_DIR) / "scenes"))
    registerDrag("own_" + file.stem().string(), std::make_shared<const Scene>(loadSceneFile(file).scene));
  // A huge image, where publishing full-size passes once dominated: a light scene, a heavy one, and a million
  // triangles.
  for (const auto& [name, scene] : scenes)
    if (name == "bunny" || name == "car" || name == "generated_1M_triangles")
      registerDrag(name + "_6400x4000", resized(*scene, 6400, 4000));
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
