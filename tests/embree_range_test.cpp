// Every number that reaches Embree is one Embree can represent, since Embree asserts on others: beyond
// kEmbreeCoordinateLimit a scene is traced by the reference BVH and a stray ray is answered without Embree, never
// dropped (a silently wrong image) and never handed over (an assertion and SIGABRT in Embree).

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>

#include "accel_backends.h"
#include "rayview/accel.h"
#include "rayview/prepared_scene.h"
#include "rayview/scene_loader.h"
#include "support/scene_builder.h"

namespace rayview {
namespace {

bool haveEmbree() { return availableAccel(AccelKind::Embree) == AccelKind::Embree; }

Scene quadAt(double size, double z) {
  Scene scene;
  scene.camera = testing::frontCamera(8);
  scene.materials.push_back(testing::plainMaterial());
  testing::addQuadFacingZ(scene, -size, -size, size, size, z, 0);
  return scene;
}

TEST(EmbreeRange, QuadAround1e19IsTracedNotDropped) {
  // Once rendered as background with Embree (its builder skips boxes beyond FLT_LARGE) and exit 0.
  const Scene scene = quadAt(1e19, -1e19);
  EXPECT_NE(embreeRangeProblem(scene, scene, scene.camera.position).find("a vertex is 1e+19 from the camera"),
            std::string::npos);
  const auto accel = buildAccel(scene, availableAccel(AccelKind::Embree), scene.camera.position);
  ASSERT_TRUE(accel);
  EXPECT_EQ(accel->kind(), AccelKind::Reference);
  const auto hit = accel->closestHit(Ray{{0, 0, 0}, {0.1, -0.2, -1}, 0.0, INFINITY});
  ASSERT_TRUE(hit.has_value());
  EXPECT_DOUBLE_EQ(hit->t, 1e19);
}

TEST(EmbreeRange, SceneWithinTheLimitStaysOnEmbree) {
  if (!haveEmbree()) GTEST_SKIP() << "built without Embree";
  const Scene scene = quadAt(1e17, -1e17);
  EXPECT_EQ(embreeRangeProblem(scene, scene, scene.camera.position), "");
  EXPECT_EQ(buildAccel(scene, AccelKind::Embree, scene.camera.position)->kind(), AccelKind::Embree);
}

TEST(EmbreeRange, RayFromBeyondTheLimitIsAnsweredWithoutEmbree) {
  if (!haveEmbree()) GTEST_SKIP() << "built without Embree";
  const Scene scene = quadAt(1, -2);
  const auto accel = buildAccel(scene, AccelKind::Embree, scene.camera.position);
  ASSERT_EQ(accel->kind(), AccelKind::Embree);
  // An origin of 1e20 once reached Embree, which asserts (SIGABRT) on it.
  const Ray far{{0.5, 0.5, 1e20}, {0, 0, -1}, 0.0, INFINITY};
  const auto hit = accel->closestHit(far);
  ASSERT_TRUE(hit.has_value());
  EXPECT_DOUBLE_EQ(hit->t, 1e20 + 2);
  EXPECT_TRUE(accel->occluded(far));
  EXPECT_FALSE(accel->occluded(Ray{{5, 5, 1e20}, {0, 0, -1}, 0.0, INFINITY}));
  EXPECT_FALSE(accel->closestHit(Ray{{0, 0, 0}, {0, 0, 1e20}, 0.0, INFINITY}).has_value());
}

TEST(EmbreeRange, ShadowRayEpsilonBeyondTheLimitIsRefusedWhereItIsWritten) {
  // <shadowrayepsilon> 1e20 once pushed every shadow ray's origin to 1e20: SIGABRT in Embree.
  const std::string xml =
      "<scene>\n<shadowrayepsilon>1e20</shadowrayepsilon>\n<camera><position>0 0 0</position><gaze>0 0 -1</gaze>"
      "<up>0 1 0</up><nearplane>-1 1 -1 1</nearplane><neardistance>1</neardistance>"
      "<imageresolution>4 4</imageresolution></camera>\n</scene>\n";
  try {
    loadSceneText(xml, "eps.xml", ".");
    FAIL() << "loaded";
  } catch (const SceneError& e) {
    EXPECT_STREQ(e.what(), "eps.xml:2: error: <shadowrayepsilon>: 1e20 is larger than any distance rayview can "
                           "trace (the limit is 1e18)");
  }
  std::string atTheLimit = xml;
  atTheLimit.replace(atTheLimit.find("1e20"), 4, "1e18");
  EXPECT_NO_THROW(loadSceneText(atTheLimit, "eps.xml", "."));
}

TEST(EmbreeRange, LargeShadowRayEpsilonWithinTheLimitFallsBack) {
  Scene scene = quadAt(1, -2);
  scene.shadowRayEpsilon = 9.9e17;
  scene.lights.of<PointLight>().push_back(PointLight{"1", {0, 0, 1e17}, Color(1, 1, 1)});
  EXPECT_NE(embreeRangeProblem(scene, scene, scene.camera.position).find("<shadowrayepsilon>"), std::string::npos);
  // The parameters (the epsilon) decide it: preparing the scene for Embree builds the reference BVH, and says why
  // (`rayview render` prints it, the viewer lists it with the scene's warnings).
  const auto prepared = prepareGeometry(scene, availableAccel(AccelKind::Embree), BvhBuild::Interactive);
  EXPECT_EQ(prepared->accel->kind(), AccelKind::Reference);
  if (haveEmbree()) {
    EXPECT_NE(prepared->accelFallback.find("<shadowrayepsilon>"), std::string::npos);
  }
}

TEST(EmbreeRange, PreparingAFarSceneSaysWhyItIsNotOnEmbree) {
  if (!haveEmbree()) GTEST_SKIP() << "built without Embree";
  const auto far = prepareGeometry(std::make_shared<const Scene>(quadAt(1e19, -1e19)), AccelKind::Embree, BvhBuild::Interactive);
  EXPECT_EQ(far->accel->kind(), AccelKind::Reference);
  EXPECT_NE(far->accelFallback.find("a vertex is 1e+19 from the camera"), std::string::npos) << far->accelFallback;
  // Within range: the fast traversal (for a scene this small, the packet BVH: the next test).
  const auto near = prepareGeometry(std::make_shared<const Scene>(quadAt(1e17, -1e17)), AccelKind::Embree, BvhBuild::Interactive);
  EXPECT_EQ(near->accel->kind(), AccelKind::Packet);
  EXPECT_EQ(near->accelFallback, "");
  // The reference BVH asked for is no fallback.
  EXPECT_EQ(prepareGeometry(std::make_shared<const Scene>(quadAt(1e19, -1e19)), AccelKind::Reference, BvhBuild::Interactive)->accelFallback, "");
}

// Asked for Embree, prepareGeometry builds rayview's packet BVH up to kPacketBvhTriangles triangles (Embree's
// start-up costs a small scene more than its traversal saves) and Embree beyond; the packet BVH beyond Embree's
// range falls back to the reference BVH as Embree does.
TEST(EmbreeRange, PreparingASmallSceneBuildsThePacketBvhAndALargerOneEmbree) {
  if (!haveEmbree()) GTEST_SKIP() << "built without Embree";
  Scene scene = quadAt(1.0, -2.0);
  while (scene.triangles.size() < kPacketBvhTriangles) testing::addQuadFacingZ(scene, -1, -1, 1, 1, -3.0, 0);
  ASSERT_EQ(scene.triangles.size(), kPacketBvhTriangles);
  EXPECT_EQ(prepareGeometry(std::make_shared<const Scene>(scene), AccelKind::Embree, BvhBuild::Interactive)->accel->kind(), AccelKind::Packet);
  testing::addQuadFacingZ(scene, -1, -1, 1, 1, -3.0, 0);
  EXPECT_EQ(prepareGeometry(std::make_shared<const Scene>(scene), AccelKind::Embree, BvhBuild::Interactive)->accel->kind(), AccelKind::Embree);
  EXPECT_EQ(prepareGeometry(std::make_shared<const Scene>(quadAt(1e19, -1e19)), AccelKind::Packet, BvhBuild::Interactive)->accel->kind(),
            AccelKind::Reference);
}

}  // namespace
}  // namespace rayview
