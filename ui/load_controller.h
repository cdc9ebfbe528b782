#pragma once
// The scene on screen and the loads that replace it: opening, reloading (F5, a file changed on disk),
// rebuilding the BVH for another traversal, the recent files and the file watch. The SceneLoaderTask reads and
// builds on its own thread; this asks it and adopts what it hands back, on the UI thread.

#include <chrono>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "file_watch.h"
#include "recent_files.h"
#include "scene_loader_task.h"
#include "scene_session.h"
#include "rayview/viewer.h"

namespace rayview {

// What a poll of the loader brought.
struct LoadEvent {
  enum class Kind { None, Failed, Rebuilt, Adopted };
  Kind kind = Kind::None;
  double readMs = 0.0, buildMs = 0.0;
  bool anotherScene = false;  // Adopted: another file, or the same one opened anew (not a reload)
};

class LoadController {
 public:
  explicit LoadController(const ViewerOptions& options);

  // Loads `path` ("" = the embedded default scene) in the background; the scene on screen stays meanwhile.
  void request(const std::string& path, bool isReload);
  void open(const std::string& path) { request(path, path == scenePath_ && session_ != nullptr); }
  // The path the user asked for last, even when that load failed: after `rayview missing.xml`, creating the file
  // and pressing F5 loads it (not the embedded default scene).
  void reload() { request(requestedPath_, requestedPath_ == scenePath_ && session_ != nullptr); }
  // Which model axis points up (--up, the Scene panel's Up axis): a model on screen is read again with it.
  ModelUpAxis modelUp() const { return options_.open.model.up; }
  void setModelUp(ModelUpAxis up);
  // The session's traversal changed and no rebuild for it was asked yet.
  bool rebuildWanted() const;
  // Prepare the geometry again for the session's traversal, in the background.
  void requestRebuild();
  // Takes the awaited outcome: a failure (the scene on screen stays), a rebuilt BVH, or a new session made with
  // this first viewport (the window view's size, or nullopt).
  LoadEvent poll(std::optional<std::pair<int, int>> viewport);
  // The watched file changed on disk (checked at most at the watch's pace): it is being reloaded. Only when
  // `enabled` (the Scene panel's "Reload when the file changes").
  bool reloadIfChanged(std::chrono::steady_clock::time_point now, bool enabled);
  // Seconds until the watch looks again, or nullopt when it watches no file.
  std::optional<double> secondsUntilNextLook(std::chrono::steady_clock::time_point now) const;

  SceneSession* session() { return session_.get(); }
  const SceneSession* session() const { return session_.get(); }
  bool loading() const { return awaitedLoad_ != 0; }
  const std::string& loadError() const { return loadError_; }
  std::string& loadError() { return loadError_; }  // the error overlay's Dismiss clears it
  const std::string& scenePath() const { return scenePath_; }
  std::uint64_t sceneSerial() const { return sceneSerial_; }
  const std::vector<Diagnostic>& warnings() const { return warnings_; }
  LoadProgress progress() const { return loader_.progress(); }
  const RecentFiles& recent() const { return recent_; }

 private:
  // The default render settings with the command line's knobs: what the first scene is loaded and rendered with.
  RenderSettings initialSettings() const;
  void adopt(LoadOutcome& outcome, std::optional<std::pair<int, int>> viewport);

  ViewerOptions options_;
  bool knobsApplied_ = false;  // the command line's knobs went into the first scene loaded
  SceneLoaderTask loader_;
  RecentFiles recent_;
  FileWatch watch_;

  // The scene on screen.
  std::unique_ptr<SceneSession> session_;
  std::string scenePath_;
  std::string requestedPath_;  // of the newest open or reload (what F5 loads), even if it failed
  std::vector<Diagnostic> warnings_;
  std::uint64_t sceneSerial_ = 0;

  // The load in progress.
  std::uint64_t awaitedLoad_ = 0;
  bool awaitedIsReload_ = false;
  std::optional<AccelKind> rebuildRequested_;
  std::string loadError_;
};

// The scene's path as messages name it: "the default scene" for the embedded one.
std::string describeScene(const std::string& path);

}  // namespace rayview
