// The window view's camera: the file's view at the area's resolution, its near plane extended, never cropped.
#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include "rayview/camera_rays.h"
#include "rayview/view_camera.h"

namespace rayview {
namespace {

Camera fileCamera() {
  Camera c;
  c.position = {1.0, 2.0, 3.0};
  c.gaze = {0.2, -0.1, -1.0};
  c.up = {0.0, 1.0, 0.0};
  c.left = -0.6, c.right = 0.4, c.bottom = -0.3, c.top = 0.45;  // off centre, aspect 4:3
  c.nearDistance = 1.5;
  c.width = 400, c.height = 300;
  return c;
}

// The ray through file pixel (i, j)'s centre is the ray through the same point of the window view's image.
void expectSameRays(const Camera& file, const Camera& window) {
  const ViewRect r = fileImageInWindowView(file, window);
  const CameraBasis fileBasis = cameraBasis(file), windowBasis = cameraBasis(window);
  for (const auto& [i, j] : {std::pair{0, 0}, {399, 0}, {0, 299}, {399, 299}, {123, 77}}) {
    const glm::dvec3 a = glm::normalize(pixelDirection(file, fileBasis, i, j));
    // pixelDirection aims at column i + 0.5: the window's continuous coordinate of the file pixel's centre, less 0.5.
    const double x = r.x + (i + 0.5) * r.width / file.width - 0.5, y = r.y + (j + 0.5) * r.height / file.height - 0.5;
    const glm::dvec3 b = glm::normalize(pixelDirection(window, windowBasis, x, y));
    EXPECT_NEAR(glm::length(a - b), 0.0, 1e-12) << "file pixel " << i << ", " << j;
  }
}

TEST(WindowView, AWiderAreaWidensThePlaneAboutItsCentreAndKeepsItsHeight) {
  const Camera file = fileCamera();
  const Camera view = windowViewCamera(file, 1000, 500);
  EXPECT_EQ(view.width, 1000);
  EXPECT_EQ(view.height, 500);
  EXPECT_DOUBLE_EQ(view.bottom, file.bottom);
  EXPECT_DOUBLE_EQ(view.top, file.top);
  EXPECT_NEAR((view.right - view.left) / (view.top - view.bottom), 2.0, 1e-12) << "square pixels";
  EXPECT_NEAR(view.left + view.right, file.left + file.right, 1e-12) << "same centre";
  EXPECT_LT(view.left, file.left);
  EXPECT_GT(view.right, file.right);
  EXPECT_EQ(view.position, file.position);
  EXPECT_EQ(view.gaze, file.gaze);
  EXPECT_EQ(view.nearDistance, file.nearDistance);
  const ViewRect r = fileImageInWindowView(file, view);
  EXPECT_NEAR(r.y, 0.0, 1e-9);
  EXPECT_NEAR(r.height, 500.0, 1e-9);
  EXPECT_NEAR(r.width, 500.0 * 4.0 / 3.0, 1e-9);
  EXPECT_NEAR(r.x, 0.5 * (1000.0 - r.width), 1e-9) << "centred";
  expectSameRays(file, view);
}

TEST(WindowView, ATallerAreaHeightensThePlaneAndKeepsItsWidth) {
  const Camera file = fileCamera();
  const Camera view = windowViewCamera(file, 300, 900);
  EXPECT_DOUBLE_EQ(view.left, file.left);
  EXPECT_DOUBLE_EQ(view.right, file.right);
  EXPECT_NEAR((view.right - view.left) / (view.top - view.bottom), 300.0 / 900.0, 1e-12);
  EXPECT_LT(view.bottom, file.bottom);
  EXPECT_GT(view.top, file.top);
  const ViewRect r = fileImageInWindowView(file, view);
  EXPECT_NEAR(r.x, 0.0, 1e-9);
  EXPECT_NEAR(r.width, 300.0, 1e-9);
  expectSameRays(file, view);
}

TEST(WindowView, TheSameAspectIsTheFilePlaneAtAnotherResolution) {
  const Camera file = fileCamera();
  const Camera view = windowViewCamera(file, 800, 600);
  EXPECT_DOUBLE_EQ(view.left, file.left);
  EXPECT_DOUBLE_EQ(view.right, file.right);
  EXPECT_DOUBLE_EQ(view.bottom, file.bottom);
  EXPECT_DOUBLE_EQ(view.top, file.top);
  expectSameRays(file, view);
}

TEST(WindowView, ADegenerateAreaOrPlaneNeverDividesByZero) {
  const Camera view = windowViewCamera(fileCamera(), 0, -5);
  EXPECT_EQ(view.width, 1);
  EXPECT_EQ(view.height, 1);
  Camera flat = fileCamera();
  flat.top = flat.bottom;  // the format refuses it; the viewer shows the problem and does not render
  const Camera kept = windowViewCamera(flat, 100, 100);
  EXPECT_EQ(kept.left, flat.left);
  EXPECT_EQ(kept.top, flat.top);
}

}  // namespace
}  // namespace rayview
