#pragma once
// Comparing with a reference image in the viewer: loading it (--compare, the Compare panel, the `compare` script
// command), the figures of each final pass, and what the image area shows instead of the render (the reference
// while Space is held, the difference with D), as textures displayed like the render.

#include <cstdint>
#include <optional>
#include <string>

#include "display_mapping.h"
#include "image_texture.h"
#include "panels.h"
#include "rayview/image_metrics.h"
#include "rayview/progressive_renderer.h"
#include "reference_compare.h"

namespace rayview {

class CompareController {
 public:
  // `pendingReference`: --compare's path, loaded once the first scene has loaded ("" for none).
  explicit CompareController(std::string pendingReference) : pendingReference_(std::move(pendingReference)) {}

  // --compare's path, once.
  std::optional<std::string> takePending();
  // Loads the reference of an image of this size (the camera's resolution; 0 before a scene): "" when it loaded,
  // else why not, naming the file (also on stderr); the previous reference stays then.
  std::string load(const std::string& path, int width, int height);
  // The figures of a final pass (a coarse one is not compared).
  void compareFinal(const ProgressiveFrame& frame);
  // The figures of the pass of this version, once computed.
  std::optional<ImageError> figuresOf(std::uint64_t version) const;
  // Why nothing can be compared ("" while something may be): `finalSize` is the final pass on screen's size.
  std::string problem(bool imageView, std::optional<std::pair<int, int>> finalSize) const;
  void toggleDifference();
  // What the image area shows instead of the pass `frame` (null: no pass yet), or null for the render itself.
  const ImageTexture* shownInstead(const ProgressiveFrame* frame, bool flipHeld, const DisplayMapping& mapping);
  // The label over the image area while it shows the reference or the difference ("" for the render).
  std::string viewLabel() const;

  const ReferenceComparison& comparison() const { return comparison_; }
  ComparePanelState& panel() { return panel_; }

 private:
  ReferenceComparison comparison_;
  ComparePanelState panel_;
  std::string pendingReference_;
  ImageTexture referenceTexture_;  // as displayed, like the render, so that Space flips between like and like
  MappedImage shownReference_;
  ImageTexture differenceTexture_;
  ImageView shownView_ = ImageView::Render;
};

}  // namespace rayview
