#pragma once
// The image in the image area: where it is placed (the window view fills the area; the image view fits the
// file's image or shows it at the user's zoom: keys 0, 1, + and -, Ctrl+wheel, Ctrl+drag), drawing it clipped to
// the area with a grid around the pixels at high zoom, and the readout of the pixel under the cursor.

#include <cmath>
#include <optional>
#include <string>
#include <utility>

#include "image_placement.h"
#include "image_texture.h"
#include "navigation_input.h"
#include "rayview/scene.h"
#include "rayview/progressive_renderer.h"
#include "reference_compare.h"
#include "viewer_layout.h"

namespace rayview {

// The window view's resolution for this layout (the image area in framebuffer pixels: on a high-DPI screen, as
// many as the screen shows), or nullopt in the image view.
inline std::optional<std::pair<int, int>> windowViewSize(const ViewerLayout& l, bool imageView) {
  if (imageView) return std::nullopt;
  return std::pair{std::max(1, static_cast<int>(std::lround(l.viewWidth * l.framebufferScale))),
                   std::max(1, static_cast<int>(std::lround(l.viewHeight * l.framebufferScale)))};
}

// What the readout names: the pass on screen, the reference and the cameras of the image shown.
struct ReadoutSource {
  const ProgressiveFrame& frame;
  const ReferenceComparison& comparison;
  const Camera* file = nullptr;      // the file's camera (committed edits); null before a scene
  const Camera* rendered = nullptr;  // the camera of the image the session renders
  bool imageView = false;
  bool frameIsRendered = false;      // the pass on screen is of the image the session renders
};

class ImageViewController {
 public:
  ImageViewController();

  // Fit, 1:1, zoom and pan were asked for (they go to the image view from the window view).
  static bool asked(const Shortcuts& shortcuts);
  // Places the image: the whole area in the window view; in the image view the file's width x height image.
  void place(ViewerLayout& layout, bool imageView, int width, int height) const;
  // Applies the image view's keys and mouse to the placement of a width x height image; true when it changed.
  bool applyShortcuts(const Shortcuts& shortcuts, const ViewerLayout& layout, int width, int height);
  // `samplesOf`: the pass when `shown` is the render's texture (one texel per block of a coarse pass).
  void drawImage(const ImageTexture& shown, const ViewerLayout& layout, const ProgressiveFrame* samplesOf) const;
  // The readout of the pixel under the cursor ("" when it is not over the image); printed on stdout when it
  // changes, with RAYVIEW_PRINT_READOUT set.
  std::string readout(const ViewerLayout& layout, const ReadoutSource& source);

 private:
  ImagePlacement placement_;
  int placedWidth_ = 0, placedHeight_ = 0;  // the image size the placement was made for
  std::optional<ImagePixel> readoutPixel_;  // the pixel under the cursor last frame, and what was shown of it
  std::string readoutText_;
  bool printReadout_ = false;               // RAYVIEW_PRINT_READOUT: tools driving the window read it on stdout
};

}  // namespace rayview
