// The habits' logic: exposure keys, the reference beside the scene, projecting scene points onto the image, and
// the wheel's dolly toward the point under the cursor.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include <glm/glm.hpp>

#include "orbit_camera.h"
#include "view_habits.h"
#include "viewer_fixtures.h"

namespace rayview {
namespace {

using viewer_testing::freshDirectory;

Camera testCamera() {
  Camera c;
  c.position = {0.0, 0.0, 5.0};
  c.gaze = {0.0, 0.0, -1.0};
  c.up = {0.0, 1.0, 0.0};
  c.left = -1.0, c.right = 1.0, c.bottom = -0.5, c.top = 0.5;
  c.nearDistance = 1.0;
  c.width = 400, c.height = 200;
  return c;
}

TEST(ViewHabits, ExposureKeysStepByHalfStopsWithinTheSlidersLimits) {
  EXPECT_DOUBLE_EQ(stepExposure(0.0, 1), 0.5);
  EXPECT_DOUBLE_EQ(stepExposure(0.5, -2), -0.5);
  EXPECT_DOUBLE_EQ(stepExposure(7.9, 1), 8.0);
  EXPECT_DOUBLE_EQ(stepExposure(-8.0, -1), -8.0);
}

TEST(ViewHabits, TheReferenceBesideTheSceneIsFound) {
  const std::filesystem::path directory = freshDirectory("reference_beside");
  const std::string scene = (directory / "cornell.xml").string();
  std::ofstream(scene) << "<scene/>";
  EXPECT_FALSE(referenceBeside(scene));
  EXPECT_FALSE(referenceBeside(""));
  std::ofstream(directory / "cornell.png") << "png";
  EXPECT_EQ(referenceBeside(scene), (directory / "cornell.png").string());
}

TEST(ViewHabits, ProjectionPutsTheGazeAtTheCentreAndTheNearPlaneCornersAtTheCorners) {
  const Camera c = testCamera();
  const auto centre = projectToScreen({0.0, 0.0, 0.0}, c, 10.0f, 20.0f, 400.0f, 200.0f);
  ASSERT_TRUE(centre);
  EXPECT_NEAR(centre->x, 210.0f, 1e-3f);
  EXPECT_NEAR(centre->y, 120.0f, 1e-3f);
  // The near plane's top-left corner (l, t) one unit ahead of the eye.
  const auto corner = projectToScreen({-1.0, 0.5, 4.0}, c, 10.0f, 20.0f, 400.0f, 200.0f);
  ASSERT_TRUE(corner);
  EXPECT_NEAR(corner->x, 10.0f, 1e-3f);
  EXPECT_NEAR(corner->y, 20.0f, 1e-3f);
  EXPECT_FALSE(projectToScreen({0.0, 0.0, 6.0}, c, 0.0f, 0.0f, 400.0f, 200.0f)) << "behind the eye";
}

TEST(ViewHabits, TheWheelDolliesTowardThePointUnderTheCursorKeepingItThere) {
  OrbitCamera orbit;
  Bounds bounds;
  bounds.add({-1.0, -1.0, -1.0});
  bounds.add({1.0, 1.0, 1.0});
  orbit.setHome(testCamera(), bounds);
  const glm::dvec3 target{0.6, 0.2, 0.5};  // off the view's centre, where the cursor is
  const Camera before = orbit.camera();
  const auto shownBefore = projectToScreen(target, before, 0.0f, 0.0f, 400.0f, 200.0f);
  orbit.dollyToward(target, 1.0);
  const Camera after = orbit.camera();
  const auto shownAfter = projectToScreen(target, after, 0.0f, 0.0f, 400.0f, 200.0f);
  EXPECT_NEAR(glm::length(target - after.position), 0.85 * glm::length(target - before.position), 1e-9);
  EXPECT_NEAR(shownAfter->x, shownBefore->x, 1e-3f) << "the point under the cursor stays under it";
  EXPECT_NEAR(shownAfter->y, shownBefore->y, 1e-3f);
  EXPECT_NEAR(glm::length(glm::normalize(after.gaze) - glm::normalize(before.gaze)), 0.0, 1e-12);
  // Many notches never reach the point.
  orbit.dollyToward(target, 200.0);
  EXPECT_GT(glm::length(target - orbit.camera().position), 0.0);
}

}  // namespace
}  // namespace rayview
