// The viewer's comparison with a reference image: loading it (--compare, the Compare panel, the `compare` script
// command), its figures for scripts, and which image the image area shows (Space, D).
#include <cstdio>
#include <filesystem>

#include "viewer_app.h"

namespace rayview {

std::string ViewerApp::loadReference(const std::string& path) {
  comparePanel_.path = path;
  comparePanel_.reveal = true;
  framesToDraw_ = kSettleFrames;
  // The reference must be the size of the image the scene renders (the camera's resolution, edits included).
  const Camera* camera = session_ ? &session_->committedEdits().camera : nullptr;
  if (!comparison_.load(path, camera ? camera->width : 0, camera ? camera->height : 0)) {
    std::fprintf(stderr, "rayview: reference not loaded: %s\n", comparison_.loadError().c_str());
    return comparison_.loadError();
  }
  std::printf("reference %s (%dx%d)\n", path.c_str(), comparison_.reference().width, comparison_.reference().height);
  std::fflush(stdout);
  // A reference is of the file's image: compare, flip and difference in the image view, pixel for pixel.
  setImageView(true);
  // A final pass already on screen is compared at once; otherwise the next final pass is.
  if (haveFrame_ && frame_.final) comparison_.compareFinal(frame_.image, frame_.version);
  return {};
}

std::optional<ImageError> ViewerApp::finalComparison() const {
  if (!finalFrameShown() || !comparison_.figures() || comparison_.figuresVersion() != frame_.version) return std::nullopt;
  std::optional<ImageError> figures = comparison_.figures();
  // A reference is of the file's camera: the figures say when the one on screen is not that any more.
  if (session_ && !(session_->committedEdits().camera == session_->loaded().camera))
    figures->cameraMismatch = "the viewer's camera is not the scene file's";
  return figures;
}

std::string ViewerApp::comparisonProblem() const {
  if (!comparison_.loaded()) return comparison_.loadError().empty() ? "no reference image" : comparison_.loadError();
  if (!display_.imageView) return "the window view is not the file's image: V (or view image) shows the image view";
  // Only the final pass counts: a pass of the previous edits may still have another resolution.
  if (finalFrameShown()) return comparison_.sizeProblem(frame_.width, frame_.height);
  return {};
}

std::string ViewerApp::viewLabel() const {
  // The file's name only: the whole path is in the Compare panel, and a long one would cover the image.
  const std::string name = std::filesystem::path(comparison_.path()).filename().string();
  if (shownView_ == ImageView::Reference) return "Reference " + name + " (Space held)";
  if (shownView_ == ImageView::Difference) return "Difference from " + name + " (D)";
  return {};
}

void ViewerApp::toggleDifference() {
  if (!comparison_.loaded()) return;  // nothing to differ from: D does nothing rather than arm a hidden state
  comparePanel_.showDifference = !comparePanel_.showDifference;
}

const ImageTexture& ViewerApp::shownImage() {
  const bool comparable = haveFrame_ && comparison_.comparable(frame_.width, frame_.height);
  const ImageView view = chooseImageView(navigation_.flipHeld(), comparePanel_.showDifference, comparable);
  if (view != shownView_) {
    shownView_ = view;
    // Tools driving the window (tests) follow what the image area shows.
    std::printf("showing %s\n", toString(view));
    std::fflush(stdout);
  }
  // The reference is displayed as the render is (exposure, gamma), so that where they agree, Space changes nothing.
  // The difference stays raw: its colours are a code (blue 1, yellow 2 to 8, red more) that exposure would break.
  switch (view) {
    case ImageView::Reference:
      referenceTexture_.update(
          shownReference_.of(comparison_.reference(), comparison_.referenceSerial(), display_.mapping),
          shownReference_.serial());
      return referenceTexture_;
    case ImageView::Difference:
      differenceTexture_.update(comparison_.difference(frame_), comparison_.differenceSerial());
      return differenceTexture_;
    case ImageView::Render:
      break;
  }
  // Again after the panels and the script: an exposure or gamma changed this frame shows this frame.
  return renderTexture();
}

}  // namespace rayview
