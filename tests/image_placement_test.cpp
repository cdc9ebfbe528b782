// The viewer's image view (ui/image_placement.h): fit, 1:1 on any screen, zoom about the cursor, pan, and the
// pixel under the cursor.
#include "image_placement.h"

#include <cmath>

#include <gtest/gtest.h>

namespace rayview {
namespace {

const ScreenRect kView{400.0, 0.0, 880.0, 800.0};  // right of the panels in a 1280x800 window

TEST(ImagePlacement, FitsTheWholeImageCentredWithItsAspect) {
  ImagePlacement p;
  const ScreenRect r = p.place(kView, 512, 256, 1.0);
  EXPECT_DOUBLE_EQ(r.width, 880.0);
  EXPECT_DOUBLE_EQ(r.height, 440.0);
  EXPECT_DOUBLE_EQ(r.x, 400.0);
  EXPECT_DOUBLE_EQ(r.y, 180.0);
  EXPECT_DOUBLE_EQ(p.zoom(kView, 512, 256, 1.0), 880.0 / 512.0);
}

TEST(ImagePlacement, OneToOneIsOneFramebufferPixelPerImagePixelOnHighDpiScreensToo) {
  for (double framebufferScale : {1.0, 2.0}) {
    ImagePlacement p;
    p.zoomAt(1.0, kView.x + kView.width / 2, kView.y + kView.height / 2, kView, 512, 256, framebufferScale);
    const ScreenRect r = p.place(kView, 512, 256, framebufferScale);
    EXPECT_DOUBLE_EQ(r.width * framebufferScale, 512.0);
    EXPECT_DOUBLE_EQ(r.height * framebufferScale, 256.0);
    // Zoomed about the view's centre from the fitted view: the image stays centred.
    EXPECT_DOUBLE_EQ(r.x + r.width / 2, kView.x + kView.width / 2);
    EXPECT_DOUBLE_EQ(r.y + r.height / 2, kView.y + kView.height / 2);
  }
}

// The image point under window point (x, y), in image pixels.
double imageX(const ScreenRect& r, int width, double x) { return (x - r.x) / r.width * width; }
double imageY(const ScreenRect& r, int height, double y) { return (y - r.y) / r.height * height; }

TEST(ImagePlacement, ZoomKeepsTheImagePointUnderTheCursorUnderIt) {
  ImagePlacement p;
  const double x = 900.0, y = 300.0;
  for (double zoom : {4.0, 16.0, 0.5}) {
    const ScreenRect before = p.place(kView, 512, 256, 1.0);
    const double u = imageX(before, 512, x), v = imageY(before, 256, y);
    p.zoomAt(zoom, x, y, kView, 512, 256, 1.0);
    EXPECT_DOUBLE_EQ(p.zoom(kView, 512, 256, 1.0), zoom);
    // Up to the half screen pixel by which the image snaps to whole pixels (exact 1:1).
    const ScreenRect r = p.place(kView, 512, 256, 1.0);
    EXPECT_LE(std::abs(imageX(r, 512, x) - u) * zoom, 0.5 + 1e-9) << zoom;
    EXPECT_LE(std::abs(imageY(r, 256, y) - v) * zoom, 0.5 + 1e-9) << zoom;
    EXPECT_EQ(r.x, std::round(r.x));
    EXPECT_EQ(r.y, std::round(r.y));
  }
  p.zoomAt(1e9, x, y, kView, 512, 256, 1.0);
  EXPECT_DOUBLE_EQ(p.zoom(kView, 512, 256, 1.0), kMaxImageZoom);
  p.fit();
  EXPECT_TRUE(p.fitted());
  EXPECT_DOUBLE_EQ(p.place(kView, 512, 256, 1.0).x, 400.0);
}

TEST(ImagePlacement, TheCursorNamesThePixelItsScreenPixelShows) {
  // The hotspot is a screen pixel's corner; that pixel shows the image pixel under its centre.
  EXPECT_DOUBLE_EQ(screenPixelCentre(723.0, 1.0), 723.5);
  EXPECT_DOUBLE_EQ(screenPixelCentre(723.9, 1.0), 723.5);
  EXPECT_DOUBLE_EQ(screenPixelCentre(361.5, 2.0), 361.75);  // framebuffer pixel 723 of a 2x screen
  const ScreenRect placed{600.25, 0.0, 480.0, 300.0};    // at 1:1, a quarter pixel off (a fitted odd layout)
  EXPECT_EQ(ImagePlacement::pixelAt(placed, 480, 300, screenPixelCentre(723.0, 1.0), 10.5), (ImagePixel{123, 10}));
}

TEST(ImagePlacement, PanMovesTheImageWithTheCursorButNeverLosesIt) {
  ImagePlacement p;
  p.zoomAt(4.0, 840.0, 400.0, kView, 512, 256, 1.0);
  const ScreenRect before = p.place(kView, 512, 256, 1.0);
  p.pan(30.0, -20.0, kView, 512, 256, 1.0);
  const ScreenRect after = p.place(kView, 512, 256, 1.0);
  EXPECT_DOUBLE_EQ(after.x - before.x, 30.0);
  EXPECT_DOUBLE_EQ(after.y - before.y, -20.0);
  p.pan(1e7, 1e7, kView, 512, 256, 1.0);  // the image's corner stops a quarter of the view past the centre
  const ScreenRect far = p.place(kView, 512, 256, 1.0);
  EXPECT_DOUBLE_EQ(far.x, kView.x + kView.width * 0.75);
  EXPECT_DOUBLE_EQ(far.y, kView.y + kView.height * 0.75);
}

TEST(ImagePlacement, PixelUnderTheCursor) {
  const ScreenRect placed{100.0, 50.0, 400.0, 200.0};  // a 4x2 image, 100 units per pixel
  EXPECT_EQ(ImagePlacement::pixelAt(placed, 4, 2, 100.0, 50.0), (ImagePixel{0, 0}));
  EXPECT_EQ(ImagePlacement::pixelAt(placed, 4, 2, 499.9, 249.9), (ImagePixel{3, 1}));
  EXPECT_EQ(ImagePlacement::pixelAt(placed, 4, 2, 250.0, 160.0), (ImagePixel{1, 1}));
  EXPECT_FALSE(ImagePlacement::pixelAt(placed, 4, 2, 500.0, 100.0));
  EXPECT_FALSE(ImagePlacement::pixelAt(placed, 4, 2, 99.0, 100.0));
  EXPECT_FALSE(ImagePlacement::pixelAt({}, 4, 2, 0.0, 0.0));
}

}  // namespace
}  // namespace rayview
