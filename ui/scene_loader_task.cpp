#include "scene_loader_task.h"

#include <chrono>
#include <new>

#include "rayview/camera_rays.h"
#include "scene_source.h"

namespace rayview {
namespace {

double msSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

SceneLoaderTask::SceneLoaderTask() : worker_([this] { workerLoop(); }) {}

SceneLoaderTask::~SceneLoaderTask() {
  {
    std::lock_guard lock(mutex_);
    stopping_ = true;
  }
  wake_.notify_all();
  worker_.join();
}

std::uint64_t SceneLoaderTask::request(LoadRequest request) {
  std::uint64_t id;
  {
    std::lock_guard lock(mutex_);
    id = ++pendingId_;
    pending_ = std::move(request);
    outcome_.reset();  // an older outcome not yet taken is stale now
    latest_ = id;      // from here on the running load's build callback cancels it
  }
  wake_.notify_all();
  return id;
}

std::optional<LoadOutcome> SceneLoaderTask::takeOutcome() {
  std::lock_guard lock(mutex_);
  std::optional<LoadOutcome> out = std::move(outcome_);
  outcome_.reset();
  return out;
}

LoadProgress SceneLoaderTask::progress() const {
  LoadProgress p;
  std::lock_guard lock(mutex_);
  p.busy = running_ || pending_.has_value();
  p.path = pending_ ? pending_->path : runningPath_;
  p.building = building_.load();
  p.fraction = fraction_.load();
  return p;
}

bool SceneLoaderTask::busy() const {
  std::lock_guard lock(mutex_);
  return running_ || pending_.has_value();
}

bool SceneLoaderTask::onBuildProgress(void* user, double fraction) {
  const BuildContext& context = *static_cast<const BuildContext*>(user);
  context.task->fraction_ = fraction;
  return !context.task->superseded(context.id);
}

void SceneLoaderTask::workerLoop() {
  for (;;) {
    LoadRequest request;
    std::uint64_t id;
    {
      std::unique_lock lock(mutex_);
      wake_.wait(lock, [&] { return stopping_.load() || pending_.has_value(); });
      if (stopping_) return;
      request = std::move(*pending_);
      pending_.reset();
      id = pendingId_;
      running_ = true;
      runningPath_ = request.path;
      building_ = false;
      fraction_ = 0.0;
    }
    LoadOutcome outcome = run(id, request);
    std::lock_guard lock(mutex_);
    running_ = false;
    // Only the newest request's outcome is shown; a superseded one is dropped here (and freed with it).
    if (id == pendingId_ && !pending_) outcome_ = std::move(outcome);
  }
}

LoadOutcome SceneLoaderTask::run(std::uint64_t id, const LoadRequest& request) {
  LoadOutcome outcome;
  outcome.id = id;
  outcome.request = request;
  try {
    std::shared_ptr<const Scene> scene = request.rebuildOf;
    if (!scene) {
      const auto readStart = std::chrono::steady_clock::now();
      LoadedScene loaded = loadSceneOrDefault(request.path, request.options);
      outcome.readMs = msSince(readStart);
      outcome.warnings = std::move(loaded.warnings);
      if (const std::string problem = cameraProblem(loaded.scene.camera); !problem.empty()) {
        outcome.error = (request.path.empty() ? std::string("default scene") : request.path) + ": error: camera: " + problem;
        return outcome;
      }
      scene = std::make_shared<const Scene>(std::move(loaded.scene));
    }
    if (superseded(id)) return outcome;

    building_ = true;
    const AccelKind accel = availableAccel(request.accel);
    BuildContext context{this, id};
    // The shared overload: the geometry keeps this scene (the tracer reads its meshes) without a copy.
    std::shared_ptr<const PreparedGeometry> geometry = prepareGeometry(scene, accel, onBuildProgress, &context);
    if (!geometry) return outcome;  // cancelled: a newer request took over
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
