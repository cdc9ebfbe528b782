#include "image_placement.h"

#include <algorithm>
#include <cmath>

namespace rayview {
namespace {

bool usable(const ScreenRect& view, int imageWidth, int imageHeight, double framebufferScale) {
  return view.width > 0.0 && view.height > 0.0 && imageWidth > 0 && imageHeight > 0 && framebufferScale > 0.0;
}

// The image point at the view's centre may go a quarter of the view beyond the image's edge: the image never
// leaves the view, and a zoom out about a point near the edge keeps that point under the cursor.
double clampCentre(double centre, int imageSide, double viewSide, double unitsPerPixel) {
  const double margin = 0.25 * viewSide / unitsPerPixel;
  return std::clamp(centre, -margin, imageSide + margin);
}

}  // namespace

double ImagePlacement::zoom(const ScreenRect& view, int imageWidth, int imageHeight, double framebufferScale) const {
  if (!usable(view, imageWidth, imageHeight, framebufferScale)) return 1.0;
  if (!fitted_) return zoom_;
  return std::min(view.width / imageWidth, view.height / imageHeight) * framebufferScale;
}

ScreenRect ImagePlacement::place(const ScreenRect& view, int imageWidth, int imageHeight,
                                 double framebufferScale) const {
  if (!usable(view, imageWidth, imageHeight, framebufferScale)) return {};
  const double unitsPerPixel = zoom(view, imageWidth, imageHeight, framebufferScale) / framebufferScale;
  const double centreX = fitted_ ? 0.5 * imageWidth : centreX_;
  const double centreY = fitted_ ? 0.5 * imageHeight : centreY_;
  ScreenRect r;
  r.width = imageWidth * unitsPerPixel;
  r.height = imageHeight * unitsPerPixel;
  r.x = view.x + 0.5 * view.width - centreX * unitsPerPixel;
  r.y = view.y + 0.5 * view.height - centreY * unitsPerPixel;
  if (!fitted_) {
    // On whole framebuffer pixels: at 1:1 (and any whole zoom) each image pixel is exactly screen pixels.
    r.x = std::round(r.x * framebufferScale) / framebufferScale;
    r.y = std::round(r.y * framebufferScale) / framebufferScale;
  }
  return r;
}

void ImagePlacement::unfit(const ScreenRect& view, int imageWidth, int imageHeight, double framebufferScale) {
  if (!fitted_) return;
  zoom_ = zoom(view, imageWidth, imageHeight, framebufferScale);
  centreX_ = 0.5 * imageWidth;
  centreY_ = 0.5 * imageHeight;
  fitted_ = false;
}

void ImagePlacement::zoomAt(double zoom, double x, double y, const ScreenRect& view, int imageWidth, int imageHeight,
                            double framebufferScale) {
  if (!usable(view, imageWidth, imageHeight, framebufferScale) || !(zoom > 0.0)) return;
  unfit(view, imageWidth, imageHeight, framebufferScale);
  const ScreenRect before = place(view, imageWidth, imageHeight, framebufferScale);
  // The image point under the cursor, in image pixels; it stays under the cursor.
  const double u = (x - before.x) / before.width * imageWidth;
  const double v = (y - before.y) / before.height * imageHeight;
  zoom_ = std::clamp(zoom, kMinImageZoom, kMaxImageZoom);
  const double unitsPerPixel = zoom_ / framebufferScale;
  centreX_ = clampCentre(u + (view.x + 0.5 * view.width - x) / unitsPerPixel, imageWidth, view.width, unitsPerPixel);
  centreY_ = clampCentre(v + (view.y + 0.5 * view.height - y) / unitsPerPixel, imageHeight, view.height, unitsPerPixel);
}

void ImagePlacement::pan(double dx, double dy, const ScreenRect& view, int imageWidth, int imageHeight,
                         double framebufferScale) {
  if (!usable(view, imageWidth, imageHeight, framebufferScale)) return;
  unfit(view, imageWidth, imageHeight, framebufferScale);
  const double unitsPerPixel = zoom_ / framebufferScale;
  centreX_ = clampCentre(centreX_ - dx / unitsPerPixel, imageWidth, view.width, unitsPerPixel);
  centreY_ = clampCentre(centreY_ - dy / unitsPerPixel, imageHeight, view.height, unitsPerPixel);
}

std::optional<ImagePixel> ImagePlacement::pixelAt(const ScreenRect& placed, int imageWidth, int imageHeight, double x,
                                                  double y) {
  if (!(placed.width > 0.0) || !(placed.height > 0.0) || imageWidth <= 0 || imageHeight <= 0) return std::nullopt;
  const double u = (x - placed.x) / placed.width, v = (y - placed.y) / placed.height;
  if (!(u >= 0.0 && u < 1.0 && v >= 0.0 && v < 1.0)) return std::nullopt;
  return ImagePixel{std::min(static_cast<int>(u * imageWidth), imageWidth - 1),
                    std::min(static_cast<int>(v * imageHeight), imageHeight - 1)};
}

}  // namespace rayview
