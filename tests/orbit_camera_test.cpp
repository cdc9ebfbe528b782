// The viewer's navigation math (ui/orbit_camera, ui/scene_framing): orbit, pan, dolly, frame, reset, what F frames.
#include "orbit_camera.h"
#include "scene_framing.h"

#include <cmath>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "rayview/camera_rays.h"

namespace rayview {
namespace {

Camera fileCamera() {
  Camera c;
  c.position = {3.2, 2.4, 5.2};
  c.gaze = {-0.5, -0.32, -1.0};  // not unit length, as files write it
  c.up = {0.0, 1.0, 0.0};        // not orthogonal to the gaze
  c.left = -0.8;
  c.right = 0.8;
  c.bottom = -0.5;
  c.top = 0.5;
  c.nearDistance = 1.2;
  c.width = 800;
  c.height = 500;
  return c;
}

Bounds unitBox(glm::dvec3 center = glm::dvec3(0.0), double half = 1.0) {
  Bounds b;
  b.add(center - glm::dvec3(half));
  b.add(center + glm::dvec3(half));
  return b;
}

OrbitCamera homeCamera() {
  OrbitCamera orbit;
  orbit.setHome(fileCamera(), unitBox());
  return orbit;
}

void expectNear(const glm::dvec3& a, const glm::dvec3& b, double tolerance) {
  EXPECT_NEAR(a.x, b.x, tolerance);
  EXPECT_NEAR(a.y, b.y, tolerance);
  EXPECT_NEAR(a.z, b.z, tolerance);
}

// The point of the near plane (u, v coordinates) that a world point projects to, SPEC section 3.
glm::dvec2 projectToNearPlane(const Camera& camera, const glm::dvec3& point) {
  const CameraBasis basis = cameraBasis(camera);
  const glm::dvec3 d = point - camera.position;
  const double depth = -glm::dot(d, basis.w);
  return {glm::dot(d, basis.u) / depth * camera.nearDistance, glm::dot(d, basis.v) / depth * camera.nearDistance};
}

TEST(OrbitCamera, StartsAsTheFileCameraExactly) {
  const OrbitCamera orbit = homeCamera();
  EXPECT_EQ(orbit.camera().position, fileCamera().position);
  EXPECT_EQ(orbit.camera().gaze, fileCamera().gaze);
  EXPECT_EQ(orbit.camera().up, fileCamera().up);
  // The pivot is on the gaze line, in front of the eye.
  const glm::dvec3 toPivot = orbit.pivot() - fileCamera().position;
  EXPECT_NEAR(glm::length(glm::cross(glm::normalize(toPivot), glm::normalize(fileCamera().gaze))), 0.0, 1e-12);
  EXPECT_GT(glm::dot(toPivot, fileCamera().gaze), 0.0);
}

TEST(OrbitCamera, OrbitKeepsTheDistanceToThePivotAndLooksAtIt) {
  OrbitCamera orbit = homeCamera();
  const double before = orbit.distance();
  const glm::dvec3 pivot = orbit.pivot();
  for (int i = 0; i < 200; ++i) orbit.orbit(0.173, (i % 7 - 3) * 0.05);
  EXPECT_NEAR(orbit.distance(), before, 1e-9 * before);
  expectNear(orbit.pivot(), pivot, 0.0);
  const Camera& c = orbit.camera();
  expectNear(glm::normalize(c.gaze), glm::normalize(pivot - c.position), 1e-12);
}

TEST(OrbitCamera, UpStaysOrthogonalAndUnitAndTheCameraStaysValid) {
  OrbitCamera orbit = homeCamera();
  for (int i = 0; i < 50; ++i) {
    orbit.orbit(0.3, 0.2);  // pitch far past the pole: clamped
    const Camera& c = orbit.camera();
    EXPECT_NEAR(glm::dot(c.up, glm::normalize(c.gaze)), 0.0, 1e-12);
    EXPECT_NEAR(glm::length(c.up), 1.0, 1e-12);
    EXPECT_EQ(cameraProblem(c), "");
    // Up keeps pointing to the world's up side: no roll, no flip over the pole.
    EXPECT_GT(glm::dot(c.up, glm::dvec3(0, 1, 0)), 0.0);
  }
}

TEST(OrbitCamera, YawMovesTheEyeToItsRightAndPitchMovesItUp) {
  OrbitCamera orbit = homeCamera();
  const CameraBasis before = cameraBasis(orbit.camera());
  const glm::dvec3 eye = orbit.camera().position;
  orbit.orbit(0.1, 0.0);
  EXPECT_GT(glm::dot(orbit.camera().position - eye, before.u), 0.0);
  const glm::dvec3 eye2 = orbit.camera().position;
  orbit.orbit(0.0, 0.1);
  EXPECT_GT(orbit.camera().position.y, eye2.y);
}

TEST(OrbitCamera, PanMovesPivotAndEyeEqually) {
  OrbitCamera orbit = homeCamera();
  const glm::dvec3 eye = orbit.camera().position, pivot = orbit.pivot();
  const glm::dvec3 gaze = orbit.camera().gaze;
  orbit.pan(0.25, -0.5);
  const glm::dvec3 eyeMove = orbit.camera().position - eye, pivotMove = orbit.pivot() - pivot;
  expectNear(eyeMove, pivotMove, 1e-12);
  EXPECT_GT(glm::length(eyeMove), 0.0);
  EXPECT_EQ(orbit.camera().gaze, gaze);  // a pan does not turn the camera
  // The move is in the image plane, scaled to the view: half a view height down is half the view's height.
  const CameraBasis basis = cameraBasis(orbit.camera());
  EXPECT_NEAR(glm::dot(eyeMove, basis.w), 0.0, 1e-12);
  const double viewHeight = (fileCamera().top - fileCamera().bottom) / fileCamera().nearDistance * orbit.distance();
  EXPECT_NEAR(glm::dot(eyeMove, basis.v), -0.5 * viewHeight, 1e-12);
  EXPECT_NEAR(glm::dot(eyeMove, basis.u), 0.25 * viewHeight, 1e-12);
}

TEST(OrbitCamera, DollyApproachesButNeverCrossesThePivot) {
  OrbitCamera orbit = homeCamera();
  const glm::dvec3 pivot = orbit.pivot();
  const glm::dvec3 towardPivot = pivot - orbit.camera().position;
  double last = orbit.distance();
  orbit.dolly(1.0);
  EXPECT_LT(orbit.distance(), last);
  for (int i = 0; i < 10000; ++i) orbit.dolly(5.0);
  EXPECT_GT(orbit.distance(), 0.0);
  EXPECT_GT(glm::dot(pivot - orbit.camera().position, towardPivot), 0.0);  // still in front of the pivot
  expectNear(orbit.pivot(), pivot, 0.0);
  last = orbit.distance();
  orbit.dolly(-3.0);
  EXPECT_GT(orbit.distance(), last);
}

TEST(OrbitCamera, FrameFitsTheBoundsInTheView) {
  for (const glm::dvec3 center : {glm::dvec3(0.0), glm::dvec3(1e6, -2e5, 3e4), glm::dvec3(-7, 3, 12)}) {
    for (const double half : {1e-4, 1.0, 1e4}) {
      OrbitCamera orbit = homeCamera();
      orbit.orbit(0.7, 0.2);
      const Bounds box = unitBox(center, half);
      orbit.frame(box);
      const Camera& c = orbit.camera();
      expectNear(orbit.pivot(), center, 1e-9 * (glm::length(center) + half));
      for (int corner = 0; corner < 8; ++corner) {
        const glm::dvec3 p{corner & 1 ? box.max.x : box.min.x, corner & 2 ? box.max.y : box.min.y,
                           corner & 4 ? box.max.z : box.min.z};
        const glm::dvec2 onPlane = projectToNearPlane(c, p);
        EXPECT_GE(onPlane.x, c.left);
        EXPECT_LE(onPlane.x, c.right);
        EXPECT_GE(onPlane.y, c.bottom);
        EXPECT_LE(onPlane.y, c.top);
      }
      // Not absurdly far either: the sphere touches (within the margin) the narrower side of the view.
      EXPECT_LT(orbit.distance(), 1.1 * box.radius() / std::sin(std::atan(fittingHalfAngleTangent(c))));
    }
  }
}

TEST(OrbitCamera, ResetRestoresTheFileCameraAndPivot) {
  OrbitCamera orbit = homeCamera();
  const glm::dvec3 pivot = orbit.pivot();
  orbit.orbit(1.0, 0.4);
  orbit.pan(0.3, 0.1);
  orbit.dolly(4.0);
  orbit.frame(unitBox(glm::dvec3(5.0), 2.0));
  orbit.reset();
  EXPECT_EQ(orbit.camera().position, fileCamera().position);
  EXPECT_EQ(orbit.camera().gaze, fileCamera().gaze);
  EXPECT_EQ(orbit.camera().up, fileCamera().up);
  EXPECT_EQ(orbit.camera().width, fileCamera().width);
  EXPECT_EQ(orbit.pivot(), pivot);
}

TEST(OrbitCamera, NumericEditsKeepThePivotDistance) {
  OrbitCamera orbit = homeCamera();
  const double distance = orbit.distance();
  Camera edited = orbit.camera();
  edited.position += glm::dvec3(1.0, 0.0, 0.0);
  edited.gaze = {0.0, 0.0, -2.0};
  orbit.setCamera(edited);
  EXPECT_EQ(orbit.camera().position, edited.position);
  expectNear(orbit.pivot(), edited.position + glm::dvec3(0, 0, -distance), 1e-12);
}

TEST(OrbitCamera, LensIsNeverChangedByNavigation) {
  OrbitCamera orbit = homeCamera();
  orbit.orbit(0.5, 0.5);
  orbit.pan(1.0, 1.0);
  orbit.dolly(2.0);
  const Camera& c = orbit.camera();
  const Camera f = fileCamera();
  EXPECT_EQ(c.left, f.left);
  EXPECT_EQ(c.right, f.right);
  EXPECT_EQ(c.bottom, f.bottom);
  EXPECT_EQ(c.top, f.top);
  EXPECT_EQ(c.nearDistance, f.nearDistance);
  EXPECT_EQ(c.width, f.width);
  EXPECT_EQ(c.height, f.height);
}

TEST(SceneBounds, CoversTheVerticesTrianglesUse) {
  Scene scene;
  scene.vertices = {{0, 0, 0}, {1, 2, 3}, {-1, 5, 0}, {100, 100, 100}};  // the last is unused
  Triangle t;
  t.vertex[0] = 0;
  t.vertex[1] = 1;
  t.vertex[2] = 2;
  scene.triangles.push_back(t);
  const Bounds b = sceneBounds(scene);
  EXPECT_FALSE(b.empty);
  EXPECT_EQ(b.min, glm::dvec3(-1, 0, 0));
  EXPECT_EQ(b.max, glm::dvec3(1, 5, 3));
  EXPECT_TRUE(sceneBounds(Scene{}).empty);
}


// A mesh of two triangles spanning the box from `low` to `high` (its bounds are that box).
void addMesh(SceneGeometry& g, const std::string& id, const glm::dvec3& low, const glm::dvec3& high) {
  const auto first = static_cast<std::uint32_t>(g.vertices.size());
  g.vertices.push_back(low);
  g.vertices.push_back({high.x, low.y, low.z});
  g.vertices.push_back(high);
  g.vertices.push_back({low.x, high.y, high.z});
  Mesh mesh;
  mesh.id = id;
  mesh.firstTriangle = static_cast<std::uint32_t>(g.triangles.size());
  mesh.triangleCount = 2;
  g.meshes.push_back(mesh);
  Triangle a, b;
  a.vertex[0] = first, a.vertex[1] = first + 1, a.vertex[2] = first + 2;
  b.vertex[0] = first, b.vertex[1] = first + 2, b.vertex[2] = first + 3;
  g.triangles.push_back(a);
  g.triangles.push_back(b);
}

TEST(Framing, AHugeFlatFloorIsLeftOutAndTheRestIsFramed) {
  SceneGeometry g;
  addMesh(g, "floor", {-100, 0, -100}, {100, 0, 100});
  addMesh(g, "car", {-2, 0, -1}, {2, 1.5, 1});
  const Bounds b = framingBounds(g, std::nullopt);
  EXPECT_EQ(b.min, glm::dvec3(-2, 0, -1));
  EXPECT_EQ(b.max, glm::dvec3(2, 1.5, 1));
  // Framed, the car fills the view instead of being a speck on the floor.
  OrbitCamera orbit = homeCamera();
  orbit.frame(b);
  EXPECT_LT(orbit.distance(), 20.0);
}

TEST(Framing, GroundPlaneRule) {
  Bounds floor;
  floor.add({-10, 0, -10});
  floor.add({10, 0.1, 10});  // 0.5 % as thick as it is wide: flat
  Bounds small;
  small.add({-1, 0, -1});
  small.add({1, 2, 1});  // largest extent 2: the floor (20) is more than 4x that
  EXPECT_TRUE(isGroundPlane(floor, small));
  Bounds thick = floor;
  thick.add({0, 0.3, 0});  // 1.5 %: a slab, not a plane
  EXPECT_FALSE(isGroundPlane(thick, small));
  Bounds big = small;
  big.add({4, 4, 4});  // the rest spans 6: the floor is not 4x larger
  EXPECT_FALSE(isGroundPlane(floor, big));
  EXPECT_FALSE(isGroundPlane(floor, Bounds{}));  // a scene that is only a plane frames the plane
}

TEST(Framing, TheSelectionWinsAndAllPlanesFrameEverything) {
  SceneGeometry g;
  addMesh(g, "floor", {-100, 0, -100}, {100, 0, 100});
  addMesh(g, "car", {-2, 0, -1}, {2, 1.5, 1});
  addMesh(g, "wheel", {1, 0, 1}, {1.5, 0.5, 1.2});
  Bounds wheel = framingBounds(g, std::size_t{2});
  EXPECT_EQ(wheel.min, glm::dvec3(1, 0, 1));
  EXPECT_EQ(wheel.max, glm::dvec3(1.5, 0.5, 1.2));
  EXPECT_EQ(framingBounds(g, std::size_t{0}).max, glm::dvec3(100, 0, 100));  // a selected floor is framed
  EXPECT_EQ(framingBounds(g, std::size_t{7}).max, glm::dvec3(2, 1.5, 1.2));  // no such mesh: as no selection
  SceneGeometry planes;
  addMesh(planes, "a", {-1, 0, -1}, {1, 0, 1});
  addMesh(planes, "b", {-1, 5, -1}, {1, 5, 1});  // neither is 4x larger than the other
  EXPECT_EQ(framingBounds(planes, std::nullopt).max, glm::dvec3(1, 5, 1));
}

}  // namespace
}  // namespace rayview
