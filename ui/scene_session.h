#pragma once
// The scene on screen: what was loaded, its prepared geometry, the user's edits and navigation, and the
// snapshot the running render uses. Widgets, input and scripts change `edits()`, `settings()` and
// `orbit()`; once per UI frame commit() compares them with what the render shows and, when they differ,
// hands back a new PixelSource to restart with. UI thread only.

#include <memory>
#include <span>
#include <optional>
#include <string>
#include <utility>

#include "edit_history.h"
#include "orbit_camera.h"
#include "rayview/pixel_source.h"
#include "rayview/knobs.h"
#include "rayview/prepared_scene.h"
#include "rayview/render_settings.h"
#include "scene_edits.h"
#include "scene_pick.h"

namespace rayview {

struct LoadedSceneParts {
  std::shared_ptr<const Scene> scene;
  std::shared_ptr<const PreparedGeometry> geometry;
  Bounds bounds;
  AccelKind accel = AccelKind::Embree;  // what the geometry was built with
};

class SceneSession {
 public:
  // `knobs` (the command line's, for the first scene) are written into the edits and settings before the
  // first render, so that the fields, the render and "Save scene as" agree.
  SceneSession(LoadedSceneParts parts, RenderSettings settings, std::span<const KnobAssignment> knobs = {});

  SceneParameters& edits() { return edits_; }
  const SceneParameters& edits() const { return edits_; }
  RenderSettings& settings() { return settings_; }
  const RenderSettings& settings() const { return settings_; }
  const Scene& loaded() const { return *parts_.scene; }
  const PreparedGeometry& geometry() const { return *parts_.geometry; }
  const Bounds& bounds() const { return parts_.bounds; }

  // Navigation: the orbit camera changes position, gaze and up; the camera fields follow at once.
  template <typename Move>
  void navigate(Move&& move) {
    move(orbit_);
    edits_.camera = orbit_.camera();
  }
  const OrbitCamera& orbit() const { return orbit_; }

  // Resolution edit that keeps the near plane's aspect (square pixels): the other side follows.
  void setResolutionKeepingAspect(int width, int height, bool widthChanged);

  // Once per frame, after input, script and widgets. Returns the source to restart with when something the
  // image depends on changed and is valid; nullptr otherwise. `problem` says why an edit is not rendered.
  std::shared_ptr<const PixelSource> commit(std::string& problem);
  // The source for what is currently committed (first display, or after new geometry).
  std::shared_ptr<const PixelSource> currentSource();

  // The window view (rayview/view_camera.h): while a size is set, the render shows the committed camera at that
  // resolution (the image area's framebuffer pixels) with its near plane extended to the area's aspect; nullopt
  // renders the file's resolution (the image view). A change restarts at the next commit(); it is no edit.
  void setViewport(std::optional<std::pair<int, int>> size);
  const std::optional<std::pair<int, int>>& viewport() const { return viewport_; }
  // The camera of what the render shows: the committed one, or its window view.
  Camera renderedCamera() const;
  // The committed edits at the file's resolution, whatever the view: what Ctrl+S saves, `rayview render`'s image.
  std::shared_ptr<const PixelSource> fileSource() const;

  // The traversal back-end the settings ask for differs from the one the geometry was built with.
  bool needsRebuild() const { return settings_.accel != parts_.accel; }
  void replaceGeometry(std::shared_ptr<const PreparedGeometry> geometry, AccelKind accel);

  // The whole scene, meshes included, with the committed edits: what is rendered, what "Save scene as"
  // writes. A copy: for saving, not for every frame.
  Scene editedScene() const;
  // The loaded scene (meshes included) shared, for preparing its geometry again.
  std::shared_ptr<const Scene> loadedShared() const { return parts_.scene; }
  bool hasPendingEdits() const;
  // The parameters the running render uses (what editedScene() holds).
  const SceneParameters& committedEdits() const { return committedEdits_; }
  // The settings it uses (the traversal: the one the geometry was built with).
  const RenderSettings& committedSettings() const { return committedSettings_; }

  // Counts edits that restarted the render (for stats and tests).
  std::uint64_t commitCount() const { return commits_; }

  // Undo and redo (edit_history.h). commit() records each committed state; while `setGesture(true)` (a drag of
  // the view or of a panel value is held) the states it commits are one step. undo() and redo() put the edits
  // and settings back; the next commit() renders them (or asks for the traversal they name: needsRebuild()).
  void setGesture(bool inGesture);
  bool undo();
  bool redo();
  const EditHistory& history() const { return history_; }

  // Picking: selects the mesh under pixel (i, j) of the file's image (the committed camera), or nothing.
  std::optional<PickResult> pick(int i, int j);
  // The same by a pixel of the rendered image (renderedCamera(): the window view's, when it is on).
  std::optional<PickResult> pickRendered(int i, int j);
  // What that pixel shows, without selecting it (the wheel dollies toward it).
  std::optional<PickResult> hitRendered(int i, int j) const;
  const std::optional<PickResult>& selection() const { return selection_; }
  // True once after a pick selected something: the Materials panel opens the picked material and scrolls to it.
  bool takeMaterialReveal() { return std::exchange(revealMaterial_, false); }
  // What F frames (scene_framing.h): the selected mesh, or the meshes that are not ground planes.
  Bounds framingBounds() const;

  // The edits differ from the file as loaded (with the command line's options) or as last saved, in more than the
  // view: quitting or opening another scene asks first. A save still writes the camera as it is.
  bool unsaved() const { return !sameApartFromTheView(edits_, savedEdits_); }
  void markSaved(const SceneParameters& saved) { savedEdits_ = saved; }
  // The edits differ from what the open file holds (as loaded, or as last written to that file): the title's `*`.
  // A save to another file (Save scene as, numbered) keeps it, since the open file did not change.
  bool differsFromFile() const { return edits_ != fileEdits_; }
  void markWrittenToFile(const SceneParameters& written) { fileEdits_ = written; }

 private:
  LoadedSceneParts parts_;
  SceneParameters edits_;
  RenderSettings settings_;
  OrbitCamera orbit_;
  SceneParameters committedEdits_;
  RenderSettings committedSettings_;
  std::shared_ptr<const SceneParameters> committed_;  // snapshot of committedEdits_ the render reads
  std::optional<std::pair<int, int>> viewport_;
  bool viewportChanged_ = false;
  std::optional<PickResult> select(std::optional<PickResult> pick);
  std::uint64_t commits_ = 0;
  EditHistory history_;
  bool gesture_ = false;
  SceneParameters savedEdits_;
  SceneParameters fileEdits_;
  std::optional<PickResult> selection_;
  bool revealMaterial_ = false;
};

}  // namespace rayview
