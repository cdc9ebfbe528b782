#include "scene_session.h"

#include <algorithm>
#include <cmath>

#include "rayview/view_camera.h"
#include "scene_framing.h"

namespace rayview {

SceneSession::SceneSession(LoadedSceneParts parts, RenderSettings settings, std::span<const KnobAssignment> knobs)
    : parts_(std::move(parts)), edits_(parts_.scene->parameters()), settings_(settings), history_(EditState{}) {
  applyKnobs(knobs, {&edits_, &settings_});
  settings_.accel = parts_.accel;  // what this build could actually build
  history_ = EditHistory(EditState{edits_, settings_});
  savedEdits_ = edits_;
  fileEdits_ = edits_;
  orbit_.setHome(parts_.scene->camera, parts_.bounds);
  committedEdits_ = edits_;
  committedSettings_ = settings_;
  // Parameters only: the tracer reads the meshes from the geometry, so an edit costs the same on a
  // 1M-triangle scene as on a cube. A render may still use the previous snapshot: it is never changed.
  committed_ = std::make_shared<const SceneParameters>(committedEdits_);
}

Scene SceneSession::editedScene() const {
  Scene scene = *parts_.scene;
  scene.parameters() = committedEdits_;
  return scene;
}

void SceneSession::setResolutionKeepingAspect(int width, int height, bool widthChanged) {
  Camera& c = edits_.camera;
  const double planeAspect = std::abs(c.right - c.left) / std::abs(c.top - c.bottom);  // width / height
  if (!(planeAspect > 0.0) || !std::isfinite(planeAspect)) {
    c.width = width;
    c.height = height;
    return;
  }
  if (widthChanged) {
    c.width = std::clamp(width, 1, kMaxViewerImageSide);
    c.height = std::clamp(static_cast<int>(std::lround(c.width / planeAspect)), 1, kMaxViewerImageSide);
  } else {
    c.height = std::clamp(height, 1, kMaxViewerImageSide);
    c.width = std::clamp(static_cast<int>(std::lround(c.height * planeAspect)), 1, kMaxViewerImageSide);
  }
}

std::shared_ptr<const PixelSource> SceneSession::commit(std::string& problem) {
  // Numeric camera fields win over navigation: the pivot follows them.
  if (edits_.camera != orbit_.camera()) orbit_.setCamera(edits_.camera);

  problem = editProblem(edits_, settings_);
  if (!problem.empty()) return nullptr;
  // What the user asked for, the traversal included (rendered now, or once the geometry is rebuilt).
  history_.record(EditState{edits_, settings_}, gesture_);
  RenderSettings renderSettings = settings_;
  renderSettings.accel = committedSettings_.accel;  // the back-end is changed by replaceGeometry()
  const bool edited = classifyEdit(committedEdits_, committedSettings_, edits_, renderSettings) == EditEffect::Restart;
  if (!edited && !viewportChanged_) return nullptr;
  if (edited) {
    committedEdits_ = edits_;
    committedSettings_ = renderSettings;
    committed_ = std::make_shared<const SceneParameters>(committedEdits_);
    ++commits_;
  }
  return currentSource();
}

std::shared_ptr<const PixelSource> SceneSession::currentSource() {
  viewportChanged_ = false;
  if (!viewport_) return fileSource();
  // The same snapshot but for the camera: a few lights and materials copied, never the meshes.
  auto shown = std::make_shared<SceneParameters>(*committed_);
  shown->camera = renderedCamera();
  return std::make_shared<TracedImage>(std::move(shown), parts_.geometry, committedSettings_);
}

std::shared_ptr<const PixelSource> SceneSession::fileSource() const {
  return std::make_shared<TracedImage>(committed_, parts_.geometry, committedSettings_);
}

void SceneSession::setViewport(std::optional<std::pair<int, int>> size) {
  if (size) size = std::pair{std::clamp(size->first, 1, kMaxViewerImageSide), std::clamp(size->second, 1, kMaxViewerImageSide)};
  if (size == viewport_) return;
  viewport_ = size;
  viewportChanged_ = true;
}

Camera SceneSession::renderedCamera() const {
  if (!viewport_) return committedEdits_.camera;
  return windowViewCamera(committedEdits_.camera, viewport_->first, viewport_->second);
}

void SceneSession::replaceGeometry(std::shared_ptr<const PreparedGeometry> geometry, AccelKind accel) {
  parts_.geometry = std::move(geometry);
  parts_.accel = accel;
  committedSettings_.accel = accel;
}

void SceneSession::setGesture(bool inGesture) {
  if (gesture_ && !inGesture) history_.endGesture();
  gesture_ = inGesture;
}

bool SceneSession::undo() {
  std::optional<EditState> state = history_.undo();
  if (!state) return false;
  edits_ = std::move(state->parameters);
  settings_ = std::move(state->settings);
  return true;
}

bool SceneSession::redo() {
  std::optional<EditState> state = history_.redo();
  if (!state) return false;
  edits_ = std::move(state->parameters);
  settings_ = std::move(state->settings);
  return true;
}

std::optional<PickResult> SceneSession::pick(int i, int j) {
  return select(pickPixel(committedEdits_.camera, *parts_.geometry, i, j));
}

std::optional<PickResult> SceneSession::pickRendered(int i, int j) {
  return select(pickPixel(renderedCamera(), *parts_.geometry, i, j));
}

std::optional<PickResult> SceneSession::hitRendered(int i, int j) const {
  return pickPixel(renderedCamera(), *parts_.geometry, i, j);
}

std::optional<PickResult> SceneSession::select(std::optional<PickResult> pick) {
  selection_ = std::move(pick);
  revealMaterial_ = selection_.has_value();
  return selection_;
}

Bounds SceneSession::framingBounds() const {
  return rayview::framingBounds(*parts_.scene,
                                selection_ ? std::optional<std::size_t>(selection_->mesh) : std::nullopt);
}

bool SceneSession::hasPendingEdits() const {
  if (viewportChanged_) return true;  // not an edit, but the image on screen is not the one asked for
  RenderSettings renderSettings = settings_;
  renderSettings.accel = committedSettings_.accel;
  return classifyEdit(committedEdits_, committedSettings_, edits_, renderSettings) != EditEffect::None;
}

}  // namespace rayview
