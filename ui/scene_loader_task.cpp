#include "scene_loader_task.h"

#include <chrono>
#include <new>

#include "rayview/camera_rays.h"
#include "rayview/scene_open.h"
#include "rayview/scene_source.h"

namespace rayview {
namespace {

double msSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

SceneLoaderTask::SceneLoaderTask()
    : worker_([this](std::uint64_t id, const LoadRequest& request, const std::atomic<bool>& cancel) {
        return run(id, request, cancel);
      }) {}

LoadProgress SceneLoaderTask::progress() const {
  LoadProgress p;
  const std::optional<LoadRequest> current = worker_.current();
  p.busy = current.has_value();
  if (current) p.path = current->path;
  p.building = building_.load();
  p.fraction = fraction_.load();
  return p;
}

LoadOutcome SceneLoaderTask::run(std::uint64_t id, const LoadRequest& request, const std::atomic<bool>& cancel) {
  building_ = false;
  fraction_ = 0.0;
  LoadOutcome outcome;
  outcome.id = id;
  outcome.request = request;
  try {
    std::shared_ptr<const Scene> scene = request.rebuildOf;
    if (!scene) {
      const auto readStart = std::chrono::steady_clock::now();
      // A model (OBJ, PLY, glTF...) is read by the import worker, a child process: its crash is an error here.
      // On every hardware thread, as the BVH's build: nothing renders the new scene until both are done.
      LoadedScene loaded = openScene(request.path, request.options, nullptr, 0);
      outcome.readMs = msSince(readStart);
      outcome.warnings = std::move(loaded.warnings);
      if (const std::string problem = cameraProblem(loaded.scene.camera); !problem.empty()) {
        outcome.error = (request.path.empty() ? std::string("default scene") : request.path) + ": error: camera: " + problem;
        return outcome;
      }
      scene = std::make_shared<const Scene>(std::move(loaded.scene));
    }
    if (cancel) return outcome;

    building_ = true;
    const AccelKind accel = availableAccel(request.accel);
    struct BuildContext {
      std::atomic<double>& fraction;
      const std::atomic<bool>& cancel;
    } context{fraction_, cancel};
    const BuildProgress onProgress = [](void* user, double fraction) {
      auto& c = *static_cast<BuildContext*>(user);
      c.fraction = fraction;
      return !c.cancel.load();
    };
    // The shared overload: the geometry keeps this scene (the tracer reads its meshes) without a copy.
    std::shared_ptr<const PreparedGeometry> geometry = prepareGeometry(scene, accel, BvhBuild::Interactive, onProgress, &context);
    if (!geometry) return outcome;  // cancelled: a newer request took over
    if (!geometry->accelFallback.empty()) {
      Diagnostic fallback;
      fallback.severity = Severity::Warning;
      fallback.where.file = request.path.empty() ? std::string("default scene") : request.path;
      fallback.message = geometry->accelFallback + "; rendering with the reference BVH instead";
      outcome.warnings.push_back(std::move(fallback));
    }
    outcome.buildMs = geometry->buildMs;
    outcome.parts.bounds = sceneBounds(*scene);
    outcome.parts.scene = std::move(scene);
    outcome.parts.geometry = std::move(geometry);
    outcome.parts.accel = accel;
    outcome.ok = true;
  } catch (const SceneError& error) {
    outcome.error = error.diagnostic().format();
  } catch (const std::bad_alloc&) {
    outcome.error = (request.path.empty() ? std::string("default scene") : request.path) +
                    ": error: not enough memory to load this scene";
  } catch (const std::exception& error) {
    outcome.error = (request.path.empty() ? std::string("default scene") : request.path) + ": error: " + error.what();
  }
  return outcome;
}

}  // namespace rayview
