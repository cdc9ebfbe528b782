#pragma once
// Loading a scene and building its BVH off the UI thread, one request at a time, on one persistent worker.
//
// A new request supersedes the one in progress: the BVH build of the old one is cancelled through its
// progress callback, and only the newest request's outcome is ever handed back. The scene on screen is
// not touched here: the UI swaps it only when a successful outcome arrives, and keeps it on failure.

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "rayview/scene_loader.h"
#include "scene_session.h"

namespace rayview {

struct LoadRequest {
  std::string path;  // "" = the embedded default scene
  LoadOptions options;
  AccelKind accel = AccelKind::Embree;
  // When set, nothing is read: only the geometry of this scene is prepared again (another back-end).
  std::shared_ptr<const Scene> rebuildOf;
};

struct LoadOutcome {
  std::uint64_t id = 0;
  LoadRequest request;
  bool ok = false;
  std::string error;  // located, as the command line prints it: "file:line: error: ..."
  std::vector<Diagnostic> warnings;
  LoadedSceneParts parts;
  double readMs = 0.0;
  double buildMs = 0.0;
};

struct LoadProgress {
  bool busy = false;
  std::string path;
  bool building = false;  // false: reading the file; true: building the BVH
  double fraction = 0.0;  // of the BVH build
};

class SceneLoaderTask {
 public:
  SceneLoaderTask();
  ~SceneLoaderTask();
  SceneLoaderTask(const SceneLoaderTask&) = delete;
  SceneLoaderTask& operator=(const SceneLoaderTask&) = delete;

  // Returns at once. Returns the request's id.
  std::uint64_t request(LoadRequest request);

  // The outcome of the newest request, once, when it is ready.
  std::optional<LoadOutcome> takeOutcome();
  LoadProgress progress() const;
  bool busy() const;

 private:
  struct BuildContext {
    SceneLoaderTask* task;
    std::uint64_t id;
  };

  void workerLoop();
  LoadOutcome run(std::uint64_t id, const LoadRequest& request);
  bool superseded(std::uint64_t id) const { return stopping_.load() || latest_.load() != id; }
  static bool onBuildProgress(void* user, double fraction);

  mutable std::mutex mutex_;
  std::condition_variable wake_;
  std::optional<LoadRequest> pending_;  // guarded by mutex_
  std::uint64_t pendingId_ = 0;         // guarded by mutex_
  bool running_ = false;                // guarded by mutex_
  std::string runningPath_;             // guarded by mutex_
  std::optional<LoadOutcome> outcome_;  // guarded by mutex_

  std::atomic<std::uint64_t> latest_{0};
  std::atomic<bool> stopping_{false};
  std::atomic<bool> building_{false};
  std::atomic<double> fraction_{0.0};

  std::thread worker_;
};

}  // namespace rayview
