#include "rayview/view_camera.h"

#include <algorithm>

namespace rayview {

Camera windowViewCamera(const Camera& file, int width, int height) {
  Camera view = file;
  view.width = std::max(width, 1);
  view.height = std::max(height, 1);
  const double planeWidth = file.right - file.left, planeHeight = file.top - file.bottom;
  if (!(planeWidth > 0.0) || !(planeHeight > 0.0)) return view;  // a camera the format refuses: left to editProblem
  const double areaAspect = static_cast<double>(view.width) / view.height;
  const double centreX = 0.5 * (file.left + file.right), centreY = 0.5 * (file.bottom + file.top);
  if (areaAspect >= planeWidth / planeHeight) {
    const double half = 0.5 * planeHeight * areaAspect;  // wider area: the plane's height fits, widen it
    view.left = centreX - half;
    view.right = centreX + half;
  } else {
    const double half = 0.5 * planeWidth / areaAspect;  // taller area: the width fits, heighten it
    view.bottom = centreY - half;
    view.top = centreY + half;
  }
  return view;
}

ViewRect fileImageInWindowView(const Camera& file, const Camera& window) {
  const double pixelsPerUnitX = window.width / (window.right - window.left);
  const double pixelsPerUnitY = window.height / (window.top - window.bottom);
  // Column 0 is at the plane's left, row 0 at its top.
  return {(file.left - window.left) * pixelsPerUnitX, (window.top - file.top) * pixelsPerUnitY,
          (file.right - file.left) * pixelsPerUnitX, (file.top - file.bottom) * pixelsPerUnitY};
}

}  // namespace rayview
