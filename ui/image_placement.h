#pragma once
// Where the image sits in the image area: fitted (the default: all of it, aspect kept) or at a zoom, in
// framebuffer pixels per image pixel (1 = 1:1, exact on high-DPI screens too), panned. Window coordinates
// are logical (GLFW's and ImGui's); `framebufferScale` converts them to framebuffer pixels. No GL, no ImGui.

#include <cmath>
#include <optional>

namespace rayview {

struct ScreenRect {
  double x = 0.0, y = 0.0, width = 0.0, height = 0.0;
};

struct ImagePixel {
  int i = 0, j = 0;  // column from the left, row from the top, as in the image file
  bool operator==(const ImagePixel&) const = default;
};

inline constexpr double kMinImageZoom = 1.0 / 64.0;
inline constexpr double kMaxImageZoom = 128.0;
// From this many framebuffer pixels per image pixel, a grid outlines the pixels.
inline constexpr double kPixelGridZoom = 8.0;

// The centre of the framebuffer pixel that window coordinate `v` falls in: the cursor's hotspot is that pixel's
// corner, the image pixel the user sees under it is the one this centre shows.
inline double screenPixelCentre(double v, double framebufferScale) {
  return (std::floor(v * framebufferScale) + 0.5) / framebufferScale;
}

class ImagePlacement {
 public:
  bool fitted() const { return fitted_; }
  void fit() { fitted_ = true; }
  // Framebuffer pixels per image pixel as the image is shown now.
  double zoom(const ScreenRect& view, int imageWidth, int imageHeight, double framebufferScale) const;

  // The image's rectangle in window coordinates (it may reach beyond the view when zoomed in).
  ScreenRect place(const ScreenRect& view, int imageWidth, int imageHeight, double framebufferScale) const;

  // A zoom of `zoom` (clamped to kMinImageZoom..kMaxImageZoom) keeping the image point under window point
  // (x, y) where it is; from the fitted view too.
  void zoomAt(double zoom, double x, double y, const ScreenRect& view, int imageWidth, int imageHeight,
              double framebufferScale);
  // The image moves by (dx, dy) window units; it never leaves the view (its edge stops a quarter of the
  // view past the view's centre).
  void pan(double dx, double dy, const ScreenRect& view, int imageWidth, int imageHeight, double framebufferScale);

  // The image pixel under window point (x, y), if the point is on the image.
  static std::optional<ImagePixel> pixelAt(const ScreenRect& placed, int imageWidth, int imageHeight, double x,
                                           double y);

 private:
  // Leaves the fitted state for an explicit zoom and centre that show the same.
  void unfit(const ScreenRect& view, int imageWidth, int imageHeight, double framebufferScale);

  bool fitted_ = true;
  double zoom_ = 1.0;                  // framebuffer pixels per image pixel, when not fitted
  double centreX_ = 0.0, centreY_ = 0.0;  // the image point (in image pixels) at the view's centre
};

}  // namespace rayview
