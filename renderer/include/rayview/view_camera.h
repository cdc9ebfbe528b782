#pragma once
// The viewer's window view: the scene file's camera shown in an area of other pixels. The area gets its own
// resolution (its framebuffer pixels, square) and the file's near plane extended about its centre to the area's
// aspect: the file's whole view stays in sight (never cropped), at the file's field of view, with more of the
// scene beside or above it. No GL.

#include "rayview/scene.h"

namespace rayview {

// `file` with resolution width x height (both >= 1) and its near plane widened or heightened to width/height,
// keeping the plane's centre and the side that already fits. Position, gaze, up and near distance are kept.
Camera windowViewCamera(const Camera& file, int width, int height);

// Where the file's image lies in the window view's image, in its pixels (fractional): the rectangle of the
// file's near plane. Used to place things known in file pixels (a reference, a pick by file pixel).
struct ViewRect {
  double x = 0.0, y = 0.0, width = 0.0, height = 0.0;
};
ViewRect fileImageInWindowView(const Camera& file, const Camera& window);

}  // namespace rayview
