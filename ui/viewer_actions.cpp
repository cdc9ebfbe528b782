// The viewer's actions, shared by keys, panels and scripts: open, reload, adopt a loaded scene, save.
#include <cstdio>
#include <filesystem>
#include <utility>

#include "numbered_file.h"
#include "widgets.h"
#include "rayview/scene_writer.h"
#include "viewer_app.h"

namespace rayview {
namespace {

std::string describe(const std::string& path) { return path.empty() ? std::string("the default scene") : path; }

// "Save scene as" starts with scene_edited.xml beside the scene, written the way the user named the scene.
std::string suggestedSaveAsPath(const std::string& scenePath) {
  const std::filesystem::path scene = std::filesystem::path(scenePath.empty() ? "default.xml" : scenePath);
  return (scene.parent_path() / (scene.stem().string() + "_edited.xml")).string();
}

}  // namespace

RenderSettings ViewerApp::initialSettings() const {
  RenderSettings settings;
  applyKnobs(options_.knobs, {nullptr, &settings});
  return settings;
}

void ViewerApp::open(const std::string& path) { requestLoad(path, path == scenePath_ && session_ != nullptr); }

// The path the user asked for last, even when that load failed: after `rayview missing.xml`, creating the file
// and pressing F5 loads it (not the embedded default scene).
void ViewerApp::reload() { requestLoad(requestedPath_, requestedPath_ == scenePath_ && session_ != nullptr); }

void ViewerApp::quit(int exitCode) {
  exitCode_ = exitCode;
  quit_ = true;
}

void ViewerApp::requestLoad(const std::string& path, bool isReload) {
  stopTradeoff("cancelled: a scene is loading", true);
  LoadRequest request;
  request.path = path;
  requestedPath_ = path;
  request.options = LoadOptions{options_.strict, true};
  request.accel = session_ ? session_->settings().accel : initialSettings().accel;
  loadError_.clear();  // the error panel shows the outcome of the newest attempt
  awaitedLoad_ = loader_.request(std::move(request));
  awaitedIsReload_ = isReload;
  rebuildRequested_.reset();
}

bool ViewerApp::pollLoader() {
  std::optional<LoadOutcome> outcome = loader_.takeOutcome();
  if (!outcome || outcome->id != awaitedLoad_) return false;
  awaitedLoad_ = 0;
  if (!outcome->ok) {
    // The scene on screen stays; the located error goes to the error panel (and stderr, for logs).
    loadError_ = outcome->error.empty() ? "cannot load " + describe(outcome->request.path) : outcome->error;
    std::fprintf(stderr, "rayview: %s\n", loadError_.c_str());
    return true;
  }
  if (outcome->request.rebuildOf) {
    if (session_) {
      session_->replaceGeometry(outcome->parts.geometry, outcome->parts.accel);
      stats_.bvhBuildMs = outcome->buildMs;
      stats_.accel = session_->geometry().accel->kind();
      restartRender(session_->currentSource());
    }
    return true;
  }
  adoptScene(*outcome);
  return true;
}

void ViewerApp::adoptScene(LoadOutcome& outcome) {
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
  navigation_.cancel();
  // The command line's knobs go into the first scene that loads, once (its depth, for one).
  std::span<const KnobAssignment> knobs;
  if (!std::exchange(knobsApplied_, true)) knobs = options_.knobs;
  session_ = std::make_unique<SceneSession>(std::move(outcome.parts), settings, knobs);
  if (keptCamera) session_->edits().camera = *keptCamera;
  // The first render is already the window view's (or the image view's), never the other one first.
  session_->setViewport(windowViewSize(layout()));
  fileImageTask_.cancel();
  awaitedFileImage_ = 0;
  fileImage_.reset();
  if (outcome.request.path != scenePath_ || !awaitedIsReload_) {
    // Another scene: the save messages were about the previous one, and a frame save still waiting for its
    // final pass would save this scene's image under the old name.
    if (filePanel_.frameSavePending) std::fprintf(stderr, "rayview: frame not saved: another scene was opened\n");
    filePanel_.frameSavePending = false;
    filePanel_.lastSaved.clear();
    filePanel_.lastSaveFailed = false;
  }
  scenePath_ = outcome.request.path;
  warnings_ = std::move(outcome.warnings);
  ++sceneSerial_;
  loadError_.clear();
  rebuildRequested_.reset();
  editProblem_.clear();

  stats_.triangles = session_->loaded().triangles.size();
  stats_.readMs = outcome.readMs;
  stats_.bvhBuildMs = outcome.buildMs;
  stats_.accel = session_->geometry().accel->kind();

  // The same file again (a reload) keeps its watch: the stamp it took when it saw the change predates this
  // read, so a change made while the file was being read still triggers another reload.
  if (watch_.path() != std::filesystem::path(scenePath_)) watch_.watch(scenePath_);
  if (!scenePath_.empty()) recent_.add(scenePath_);
  filePanel_.openPath = scenePath_;
  if (filePanel_.saveScenePath.empty() || !awaitedIsReload_)
    filePanel_.saveScenePath = suggestedSaveAsPath(scenePath_);

  std::printf("loaded %s (%s, %s)\n", describe(scenePath_).c_str(), counted(stats_.triangles, "triangle").c_str(),
              counted(warnings_.size(), "warning").c_str());
  std::fflush(stdout);
  // A kept camera is committed before the first restart, so the file's view never flashes up.
  std::shared_ptr<const PixelSource> source = session_->commit(editProblem_);
  restartRender(source ? std::move(source) : session_->currentSource());
}

bool ViewerApp::pollFileWatch(Clock::time_point now) {
  if (!filePanel_.reloadOnChange || loading() || !watch_.changed(now)) return false;
  std::printf("reloading %s (changed on disk)\n", scenePath_.c_str());
  std::fflush(stdout);
  reload();
  return true;
}

bool ViewerApp::fileImageReady() {
  if (!finalFrameShown()) return false;
  if (display_.imageView) return true;  // the final pass on screen is the file's image
  const FileImageKey key = fileImageKey();
  if (fileImage_ && fileImageOf_ == key) return true;
  if (awaitedFileImage_ == 0 || awaitedFileImageKey_ != key) {
    awaitedFileImage_ = fileImageTask_.start(session_->fileSource());
    awaitedFileImageKey_ = key;
  }
  return false;
}

ViewerApp::FileImageKey ViewerApp::fileImageKey() const {
  return {sceneSerial_, session_ ? session_->commitCount() : 0, session_ ? &session_->geometry() : nullptr};
}

bool ViewerApp::pollFileImage() {
  std::optional<FileImageResult> result = fileImageTask_.takeResult();
  if (!result || result->id != awaitedFileImage_) return false;
  awaitedFileImage_ = 0;
  if (!result->error.empty()) {
    reportSaveFailure(ImageIoError(result->error));
    return true;
  }
  if (result->cancelled) return true;
  fileImage_ = std::move(result->image);
  fileImageOf_ = awaitedFileImageKey_;
  std::printf("rendered the file's image %dx%d for saving in %.0f ms\n", fileImage_->width, fileImage_->height,
              result->renderMs);
  std::fflush(stdout);
  return true;
}

const Image& ViewerApp::fileImage() const { return display_.imageView ? frame_.image : *fileImage_; }

std::filesystem::path ViewerApp::saveFrame(const std::string& path, FrameSave what) {
  if (!haveFrame_) throw ImageIoError("no frame to save yet");
  // Callers wait for it: the final pass (image view) or the file's image rendered after it (window view); never a
  // coarse pass, which holds one sample per block, nor the window's other resolution.
  if (!fileImageReady()) throw ImageIoError("the file's image is not rendered yet");
  // Raw: as `rayview render` writes it. Displayed: with the exposure and gamma on screen, which at their defaults
  // is the same image.
  Image mapped;
  if (what == FrameSave::Displayed) mapped = mapForDisplay(fileImage(), display_.mapping);
  const Image& image = what == FrameSave::Displayed ? mapped : fileImage();
  std::filesystem::path saved = path;
  if (path.empty()) saved = saveFrameNumbered(image, scenePath_, what);
  else writeImageFile(refusingInputs(path, scenePath_, session_ ? &session_->loaded() : nullptr), image);
  filePanel_.frameSavePending = false;
  filePanel_.lastSaveFailed = false;
  filePanel_.lastSaved = "saved " + saved.string();
  if (what == FrameSave::Displayed) filePanel_.lastSaved += " (as displayed: " + describe(display_.mapping) + ")";
  std::printf("saved %s\n", saved.string().c_str());
  std::fflush(stdout);
  return saved;
}

std::filesystem::path ViewerApp::saveScene(const std::string& path) {
  if (!session_) throw ImageIoError("no scene to save yet");
  // What is on screen: the committed edits (identical to the fields unless a field holds an invalid value).
  const SceneParameters& parameters = session_->committedEdits();
  std::filesystem::path saved = path;
  if (path.empty()) saved = saveSceneNumbered(parameters, session_->loaded(), scenePath_);
  else writeSceneFile(path, parameters, session_->loaded());
  session_->markSaved(parameters);
  filePanel_.lastSaveFailed = false;
  filePanel_.lastSaved = "saved scene " + saved.string();
  std::printf("saved scene %s\n", saved.string().c_str());
  std::fflush(stdout);
  return saved;
}

void ViewerApp::reportSaveFailure(const std::exception& error) {
  filePanel_.frameSavePending = false;
  filePanel_.lastSaveFailed = true;
  filePanel_.lastSaved = std::string("not saved: ") + error.what();
  std::fprintf(stderr, "rayview: %s\n", filePanel_.lastSaved.c_str());
}

void ViewerApp::saveFrameReporting() {
  // Ctrl+S saves the file's image, identical to `rayview render`, never a coarse pass. While refining, the render
  // goes on and the save happens when the final pass is on screen (afterSwap); in the window view the file's
  // image is then rendered in the background, its progress in the Save panel.
  if (!fileImageReady()) {
    if (!filePanel_.frameSavePending) {
      filePanel_.frameSavePending = true;
      filePanel_.lastSaveFailed = false;
      filePanel_.lastSaved = "saving when the final pass is ready...";
      std::printf("saving when the final pass is ready\n");
      std::fflush(stdout);
    }
    return;
  }
  try {
    saveFrame({}, filePanel_.saveFrameDisplayed ? FrameSave::Displayed : FrameSave::Raw);
  } catch (const std::exception& error) {
    reportSaveFailure(error);
  }
}

void ViewerApp::saveSceneReporting(const std::string& path) {
  try {
    saveScene(path);
  } catch (const std::exception& error) {
    reportSaveFailure(error);
  }
}

std::string ViewerApp::stateLine() const {
  auto vector = [](const glm::dvec3& v) {
    return formatNumber(v.x) + "," + formatNumber(v.y) + "," + formatNumber(v.z);
  };
  std::string line = "state generation=" + std::to_string(generation_) +
                     " stride=" + std::to_string(haveFrame_ ? frame_.stride : 0) +
                     " samples=" + std::to_string(haveFrame_ ? frame_.samples.done : 0) + "/" +
                     std::to_string(haveFrame_ ? frame_.samples.total : 0) +
                     " final=" + (finalFrameShown() ? "1" : "0") + " view=" + (display_.imageView ? "image" : "window") +
                     " shown=" + std::to_string(haveFrame_ ? frame_.width : 0) + "x" +
                     std::to_string(haveFrame_ ? frame_.height : 0);
  if (session_) {
    const Camera& c = session_->edits().camera;
    line += " position=" + vector(c.position) + " gaze=" + vector(c.gaze) + " up=" + vector(c.up) +
            " resolution=" + std::to_string(c.width) + "x" + std::to_string(c.height) +
            " depth=" + std::to_string(session_->edits().maxRayDepth) +
            " tri_light=" + std::string(toString(session_->settings().triangularLightModel)) +
            " light_samples=" + std::to_string(session_->settings().lightSamples) +
            " unsaved=" + (session_->unsaved() ? "1" : "0") +
            " undo=" + std::to_string(session_->history().undoSteps()) +
            " redo=" + std::to_string(session_->history().redoSteps()) + " picked=" +
            (session_->selection() && session_->selection()->mesh < session_->loaded().meshes.size()
                 ? session_->loaded().meshes[session_->selection()->mesh].id
                 : std::string("none"));
  }
  char timings[96];
  std::snprintf(timings, sizeof timings, " first_pass_ms=%.1f final_pass_ms=%.1f", stats_.editToFirstPassMs,
                stats_.editToFinalPassMs);
  line += timings;
  char memory[64];
  std::snprintf(memory, sizeof memory, " memory_mib=%.1f peak_mib=%.1f",
                static_cast<double>(stats_.residentBytes) / (1 << 20),
                static_cast<double>(stats_.peakResidentBytes) / (1 << 20));
  line += memory;
  line += " exposure=" + formatNumber(display_.mapping.exposureStops) +
          " gamma=" + formatNumber(display_.mapping.gamma);
  if (session_) line += " traversal=" + std::string(toString(stats_.accel));
  line += " error=" + std::string(loadError_.empty() ? "0" : "1");
  line += " scene=" + describe(scenePath_);
  return line;
}

}  // namespace rayview
