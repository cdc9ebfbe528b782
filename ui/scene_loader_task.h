#pragma once
// Loading a scene and building its BVH off the UI thread, one request at a time, on one persistent worker
// (RequestWorker).
//
// A new request supersedes the one in progress: the BVH build of the old one is cancelled through its
// progress callback, and only the newest request's outcome is ever handed back. The scene on screen is
// not touched here: the UI swaps it only when a successful outcome arrives, and keeps it on failure.

#include <atomic>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "rayview/scene_open.h"
#include "request_worker.h"
#include "scene_session.h"

namespace rayview {

struct LoadRequest {
  std::string path;  // "" = the embedded default scene
  SceneOpenOptions options;
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

  // Returns at once. Returns the request's id.
  std::uint64_t request(LoadRequest request) { return worker_.submit(std::move(request)); }

  // The outcome of the newest request, once, when it is ready.
  std::optional<LoadOutcome> takeOutcome() { return worker_.take(); }
  LoadProgress progress() const;
  bool busy() const { return worker_.busy(); }

 private:
  LoadOutcome run(std::uint64_t id, const LoadRequest& request, const std::atomic<bool>& cancel);

  std::atomic<bool> building_{false};
  std::atomic<double> fraction_{0.0};
  RequestWorker<LoadRequest, LoadOutcome> worker_;  // last: its thread uses the members above
};

}  // namespace rayview
