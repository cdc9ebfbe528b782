// The viewer's comparison with a reference image: loading, figures per final pass, Space and D.
#include "compare_controller.h"

#include <cstdio>
#include <filesystem>
#include <utility>

namespace rayview {

std::optional<std::string> CompareController::takePending() {
  if (pendingReference_.empty()) return std::nullopt;
  return std::exchange(pendingReference_, {});
}

std::string CompareController::load(const std::string& path, int width, int height) {
  panel_.path = path;
  panel_.reveal = true;
  if (!comparison_.load(path, width, height)) {
    std::fprintf(stderr, "rayview: reference not loaded: %s\n", comparison_.loadError().c_str());
    return comparison_.loadError();
  }
  std::printf("reference %s (%dx%d)\n", path.c_str(), comparison_.reference().width, comparison_.reference().height);
  std::fflush(stdout);
  return {};
}

void CompareController::compareFinal(const ProgressiveFrame& frame) {
  if (frame.final) comparison_.compareFinal(frame.image, frame.version);
}

std::optional<ImageError> CompareController::figuresOf(std::uint64_t version) const {
  if (!comparison_.figures() || comparison_.figuresVersion() != version) return std::nullopt;
  return comparison_.figures();
}

std::string CompareController::problem(bool imageView, std::optional<std::pair<int, int>> finalSize) const {
  if (!comparison_.loaded()) return comparison_.loadError().empty() ? "no reference image" : comparison_.loadError();
  if (!imageView) return "the window view is not the file's image: V (or view image) shows the image view";
  // Only the final pass counts: a pass of the previous edits may still have another resolution.
  if (finalSize) return comparison_.sizeProblem(finalSize->first, finalSize->second);
  return {};
}

std::string CompareController::viewLabel() const {
  // The file's name only: the whole path is in the Compare panel, and a long one would cover the image.
  const std::string name = std::filesystem::path(comparison_.path()).filename().string();
  if (shownView_ == ImageView::Reference) return "Reference " + name + " (Space held)";
  if (shownView_ == ImageView::Difference) return "Difference from " + name + " (D)";
  return {};
}

void CompareController::toggleDifference() {
  if (!comparison_.loaded()) return;  // nothing to differ from: D does nothing rather than arm a hidden state
  panel_.showDifference = !panel_.showDifference;
}

const ImageTexture* CompareController::shownInstead(const ProgressiveFrame* frame, bool flipHeld,
                                                    const DisplayMapping& mapping) {
  const bool comparable = frame && comparison_.comparable(frame->width, frame->height);
  const ImageView view = chooseImageView(flipHeld, panel_.showDifference, comparable);
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
      referenceTexture_.update(shownReference_.of(comparison_.reference(), comparison_.referenceSerial(), mapping),
                               shownReference_.serial());
      return &referenceTexture_;
    case ImageView::Difference:
      differenceTexture_.update(comparison_.difference(*frame), comparison_.differenceSerial());
      return &differenceTexture_;
    case ImageView::Render:
      break;
  }
  return nullptr;
}

}  // namespace rayview
