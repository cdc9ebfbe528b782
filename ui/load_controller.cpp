// Loading, reloading and rebuilding the scene on screen; the file watch and the recent files.
#include "load_controller.h"

#include <cstdio>
#include <filesystem>
#include <span>

#include "rayview/model_options.h"
#include "widgets.h"

namespace rayview {

std::string describeScene(const std::string& path) { return path.empty() ? std::string("the default scene") : path; }

LoadController::LoadController(const ViewerOptions& options)
    : options_(options), recent_(RecentFiles::defaultStorage()) {}

RenderSettings LoadController::initialSettings() const {
  RenderSettings settings;
  applyKnobs(options_.knobs, {nullptr, &settings});
  return settings;
}

void LoadController::request(const std::string& path, bool isReload) {
  LoadRequest request;
  request.path = path;
  requestedPath_ = path;
  request.options = options_.open;
  request.accel = session_ ? session_->settings().accel : initialSettings().accel;
  loadError_.clear();  // the error panel shows the outcome of the newest attempt
  awaitedLoad_ = loader_.request(std::move(request));
  awaitedIsReload_ = isReload;
  rebuildRequested_.reset();
}

void LoadController::setModelUp(ModelUpAxis up) {
  if (up == options_.open.model.up) return;
  options_.open.model.up = up;
  // The model on screen, not a newer path that failed to open.
  if (session_ && isModelFile(scenePath_)) request(scenePath_, true);
}

bool LoadController::rebuildWanted() const {
  return session_ && session_->needsRebuild() && !loading() && rebuildRequested_ != session_->settings().accel;
}

void LoadController::requestRebuild() {
  rebuildRequested_ = session_->settings().accel;
  LoadRequest request;
  request.path = scenePath_;
  request.accel = session_->settings().accel;
  request.rebuildOf = session_->loadedShared();
  awaitedLoad_ = loader_.request(std::move(request));
  awaitedIsReload_ = false;
}

LoadEvent LoadController::poll(std::optional<std::pair<int, int>> viewport) {
  std::optional<LoadOutcome> outcome = loader_.takeOutcome();
  if (!outcome || outcome->id != awaitedLoad_) return {};
  awaitedLoad_ = 0;
  LoadEvent event;
  event.readMs = outcome->readMs;
  event.buildMs = outcome->buildMs;
  if (!outcome->ok) {
    // The scene on screen stays; the located error goes to the error panel (and stderr, for logs).
    loadError_ = outcome->error.empty() ? "cannot load " + describeScene(outcome->request.path) : outcome->error;
    std::fprintf(stderr, "rayview: %s\n", loadError_.c_str());
    event.kind = LoadEvent::Kind::Failed;
    return event;
  }
  if (outcome->request.rebuildOf) {
    if (!session_) return {};
    session_->replaceGeometry(outcome->parts.geometry, outcome->parts.accel);
    event.kind = LoadEvent::Kind::Rebuilt;
    return event;
  }
  event.kind = LoadEvent::Kind::Adopted;
  event.anotherScene = outcome->request.path != scenePath_ || !awaitedIsReload_;
  adopt(*outcome, viewport);
  return event;
}

void LoadController::adopt(LoadOutcome& outcome, std::optional<std::pair<int, int>> viewport) {
  RenderSettings settings = initialSettings();
  std::optional<Camera> keptCamera;
  if (session_) {
    // Later scenes keep the user's render settings, except the light samples: another scene's lights need their
    // own count (128 on a small scene can be minutes on a big one), so they go back to the command line's.
    // The depth is each scene's own.
    settings = session_->settings();
    if (!awaitedIsReload_) settings.lightSamples = initialSettings().lightSamples;
    // A reload keeps the user's view unless the file's own camera changed.
    if (awaitedIsReload_ && session_->loaded().camera == outcome.parts.scene->camera)
      keptCamera = session_->edits().camera;
  }
  // The command line's knobs go into the first scene that loads, once (its depth, for one).
  std::span<const KnobAssignment> knobs;
  if (!std::exchange(knobsApplied_, true)) knobs = options_.knobs;
  session_ = std::make_unique<SceneSession>(std::move(outcome.parts), settings, knobs);
  if (keptCamera) session_->edits().camera = *keptCamera;
  // The first render is already the window view's (or the image view's), never the other one first.
  session_->setViewport(viewport);
  scenePath_ = outcome.request.path;
  warnings_ = std::move(outcome.warnings);
  ++sceneSerial_;
  loadError_.clear();
  rebuildRequested_.reset();
  // The same file again (a reload) keeps its watch: the stamp it took when it saw the change predates this
  // read, so a change made while the file was being read still triggers another reload.
  if (watch_.path() != std::filesystem::path(scenePath_)) watch_.watch(scenePath_);
  if (!scenePath_.empty()) recent_.add(scenePath_);
  std::printf("loaded %s (%s, %s)\n", describeScene(scenePath_).c_str(),
              counted(session_->loaded().triangles.size(), "triangle").c_str(),
              counted(warnings_.size(), "warning").c_str());
  std::fflush(stdout);
}

bool LoadController::reloadIfChanged(std::chrono::steady_clock::time_point now, bool enabled) {
  if (!enabled || loading() || !watch_.changed(now)) return false;
  std::printf("reloading %s (changed on disk)\n", scenePath_.c_str());
  std::fflush(stdout);
  reload();
  return true;
}

std::optional<double> LoadController::secondsUntilNextLook(std::chrono::steady_clock::time_point now) const {
  if (!watch_.active()) return std::nullopt;
  return watch_.secondsUntilNextLook(now);
}

}  // namespace rayview
