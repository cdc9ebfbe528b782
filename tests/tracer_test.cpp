// The Whitted integrator against values worked out by hand (SPEC sections 3-5).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <thread>

#include <glm/geometric.hpp>

#include "accel_backends.h"
#include "rayview/lean_memory.h"
#include "rayview/knobs.h"
#include "rayview/camera_cull.h"
#include "rayview/camera_rays.h"
#include "rayview/frame_renderer.h"
#include "rayview/grid_render.h"
#include "rayview/prepared_scene.h"
#include "support/scene_builder.h"

namespace rayview {
namespace {

using testing::addQuadFacingZ;
using testing::addTriangle;
using testing::frontCamera;
using testing::plainMaterial;

// Radiance of the centre pixel of a 3x3 image: its ray goes exactly down -z.
Color centrePixel(const Scene& scene, const RenderSettings& settings = {}, RayCounts* countsOut = nullptr) {
  auto geometry = prepareGeometry(scene, settings.accel, BvhBuild::Interactive);
  Tracer tracer(scene, *geometry->accel, geometry->shading, settings);
  RayCounts counts;
  const Color c = tracer.tracePixel(1, 1, counts);
  if (countsOut) *countsOut = counts;
  return c;
}

Scene quadScene(const Material& material) {
  Scene scene;
  scene.camera = frontCamera(3);
  scene.materials.push_back(material);
  addQuadFacingZ(scene, -10, -10, 10, 10, -2, 0);
  return scene;
}

TEST(CameraBasis, AxisAlignedCamera) {
  Camera camera = frontCamera(3);
  const CameraBasis b = cameraBasis(camera);
  EXPECT_EQ(b.u, glm::dvec3(1, 0, 0));
  EXPECT_EQ(b.v, glm::dvec3(0, 1, 0));
  EXPECT_EQ(b.w, glm::dvec3(0, 0, 1));
  EXPECT_EQ(pixelDirection(camera, b, 1, 1), glm::dvec3(0, 0, -1));
  // Column 0 is on the left (l), row 0 at the top (t).
  const glm::dvec3 topLeft = pixelDirection(camera, b, 0, 0);
  EXPECT_LT(topLeft.x, 0.0);
  EXPECT_GT(topLeft.y, 0.0);
}

TEST(CameraBasis, TiltedUpIsReorthogonalised) {
  Camera camera = frontCamera(3);
  camera.up = {0.2, 1.0, 0.3};
  const CameraBasis b = cameraBasis(camera);
  EXPECT_NEAR(glm::dot(b.v, b.w), 0.0, 1e-12);
  EXPECT_NEAR(glm::dot(b.u, b.w), 0.0, 1e-12);
  EXPECT_NEAR(glm::length(b.v), 1.0, 1e-12);
  EXPECT_GT(b.v.y, 0.9);
}

TEST(CameraBasis, DegenerateCamerasAreRefused) {
  Camera camera = frontCamera(3);
  camera.up = {0, 0, -2};
  EXPECT_NE(cameraProblem(camera), "");
  EXPECT_THROW(cameraBasis(camera), std::invalid_argument);
  camera = frontCamera(3);
  camera.gaze = {0, 0, 0};
  EXPECT_NE(cameraProblem(camera), "");
  camera = frontCamera(3);
  camera.left = camera.right = 1;
  EXPECT_NE(cameraProblem(camera), "");
  camera = frontCamera(3);
  camera.nearDistance = 0;
  EXPECT_NE(cameraProblem(camera), "");
}

TEST(Shading, AmbientDiffuseSpecularFromAPointLight) {
  Material m = plainMaterial();
  m.ambient = Color(0.1f);
  m.diffuse = Color(0.5f);
  m.specular = Color(0.25f);
  m.phongExponent = 1.0f;
  Scene scene = quadScene(m);
  scene.ambientLight = Color(20.0f);
  scene.lights.of<PointLight>().push_back({"1", {0, 0, 0}, Color(1000.0f)});
  // E = 1000 / 2^2 = 250; n.l = 1; h = n: 0.1*20 + 0.5*250 + 0.25*250.
  EXPECT_NEAR(centrePixel(scene).x, 2.0f + 125.0f + 62.5f, 1e-3f);
}

// A face wound away from the camera (a model's inward faces): black but for ambient light when one-sided, lit as
// its front when the material is two-sided; a face seen from the front is the same either way.
TEST(Shading, TwoSidedMaterialsLightTheBackOfAFace) {
  Material m = plainMaterial();
  m.diffuse = Color(0.5f);
  Scene scene;
  scene.camera = frontCamera(3);
  scene.materials.push_back(m);
  addTriangle(scene, {-10, -10, -2}, {0, 10, -2}, {10, -10, -2}, 0);  // clockwise from the eye: facing away
  scene.lights.of<PointLight>().push_back({"1", {0, 0, 0}, Color(1000.0f)});
  EXPECT_EQ(centrePixel(scene), Color(0.0f));
  scene.materials[0].twoSided = true;
  EXPECT_NEAR(centrePixel(scene).x, 0.5f * 250.0f, 1e-3f);  // E = 1000 / 2^2, n.l = 1 once n faces the eye

  Scene front = quadScene(m);
  front.lights = scene.lights;
  const Color oneSided = centrePixel(front);
  front.materials[0].twoSided = true;
  EXPECT_EQ(centrePixel(front), oneSided);
}

TEST(Shading, PhongExponentSharpensTheHighlight) {
  Material m = plainMaterial();
  m.ambient = m.diffuse = Color(0.0f);
  m.specular = Color(1.0f);
  m.phongExponent = 50.0f;
  Scene scene = quadScene(m);
  scene.lights.of<PointLight>().push_back({"1", {2, 0, 0}, Color(1000.0f)});
  // l = normalize(2,0,2), v = (0,0,1): h = normalize(l + v); E = 1000 / 8.
  const glm::dvec3 l = glm::normalize(glm::dvec3(2, 0, 2));
  const glm::dvec3 h = glm::normalize(l + glm::dvec3(0, 0, 1));
  EXPECT_NEAR(centrePixel(scene).x, 125.0 * std::pow(h.z, 50.0), 1e-3);
}

TEST(Shading, HardShadowBehindAnOccluder) {
  Scene scene = quadScene(plainMaterial());
  scene.ambientLight = Color(7.0f);
  scene.lights.of<PointLight>().push_back({"1", {0, 5, -2.5}, Color(1000.0f)});
  // A blocker between the light and the centre of the quad, out of the camera's way.
  addTriangle(scene, {-1, 2, -3}, {1, 2, -3}, {0, 2, -1}, 0);
  EXPECT_NEAR(centrePixel(scene).x, 7.0f, 1e-4f);
}

// A light just behind a face's plane that its tilted vertex normals still turn toward: it lights the face, and
// the shadow ray must start on the light's side of the face (behind the geometric normal, SPEC section 6), or it
// crosses the face itself and the light is lost. Both shading paths: the scalar one (tracePixel) and the one that
// shades a block's hits four at a time (tracePixels, used when all lights are point lights).
TEST(Shading, ShadowRayStartsOnTheLightsSideWhenTheShadingNormalTurnsToALightBehindTheFace) {
  Material m = plainMaterial();
  m.ambient = Color(0.0f);
  m.diffuse = Color(1.0f);
  Scene scene = quadScene(m);
  const glm::vec3 tilted = glm::normalize(glm::vec3(1.0f, 0.0f, 0.2f));
  scene.normals.push_back(tilted);
  FaceAttributes attributes;
  for (std::int32_t& n : attributes.normal) n = 0;
  scene.faceAttributes.assign(scene.triangles.size(), attributes);
  const glm::dvec3 light(10.0, 0.0, -2.5);  // 0.5 behind the quad's plane z = -2
  scene.lights.of<PointLight>().push_back({"1", light, Color(1000.0f)});

  // The centre pixel's hit is (0, 0, -2): E = 1000 / |light - hit|^2, times max(0, n.l).
  const glm::dvec3 toLight = light - glm::dvec3(0.0, 0.0, -2.0);
  const glm::dvec3 l = glm::normalize(toLight);
  ASSERT_LT(l.z, 0.0);  // behind the geometric normal (0, 0, 1) ...
  const double lit = 1000.0 / glm::dot(toLight, toLight) * glm::dot(glm::dvec3(tilted), l);
  ASSERT_GT(lit, 1.0);  // ... in front of the shading normal
  EXPECT_NEAR(centrePixel(scene).x, lit, 1e-3 * lit);

  auto geometry = prepareGeometry(scene, AccelKind::Embree, BvhBuild::Interactive);
  const Tracer tracer(scene, *geometry->accel, geometry->shading, RenderSettings{});
  PixelXY block[9];
  for (int n = 0; n < 9; ++n) block[n] = {n % 3, n / 3};
  Color together[9];
  RayCounts counts;
  tracer.tracePixels(block, 9, together, counts);
  EXPECT_NEAR(together[4].x, lit, 1e-3 * lit);
  EXPECT_EQ(counts.shadow, 9u);  // every pixel sees the lit quad and sends its shadow ray
}

TriangularLight lightAboveCentre(float intensity) {
  // n_L = normalize((v1-v2) x (v1-v3)) = (0,0,-1): it shines toward -z, onto the quad. Centroid (0,-1/3,0).
  return TriangularLight{"t", {0, 1, 0}, {1, -1, 0}, {-1, -1, 0}, Color(intensity)};
}

TEST(TriangularLight, AreaModelWithOneSampleIsTheCentroid) {
  Scene scene = quadScene(plainMaterial());
  scene.materials[0].ambient = Color(0.0f);
  scene.lights.of<TriangularLight>().push_back(lightAboveCentre(900.0f));
  // y = (0,-1/3,0), p = (0,0,-2): d^2 = 37/9, n_L.omega = n.l = 6/sqrt(37): E = 900 (6/sqrt37) / (37/9).
  const double expected = 900.0 * (36.0 / 37.0) * (9.0 / 37.0);
  EXPECT_NEAR(centrePixel(scene).x, expected, 1e-3);
}

TEST(TriangularLight, AreaModelIsOneSided) {
  Scene scene = quadScene(plainMaterial());
  scene.materials[0].ambient = Color(0.0f);
  TriangularLight light = lightAboveCentre(900.0f);
  std::swap(light.vertex2, light.vertex3);  // now it shines toward +z, away from the quad
  scene.lights.of<TriangularLight>().push_back(light);
  EXPECT_EQ(centrePixel(scene).x, 0.0f);
}

TEST(TriangularLight, AreaModelSamplesConvergeToTheIntegral) {
  Scene scene = quadScene(plainMaterial());
  scene.materials[0].ambient = Color(0.0f);
  scene.lights.of<TriangularLight>().push_back(lightAboveCentre(900.0f));
  RenderSettings settings;
  settings.lightSamples = 256;
  const float many = centrePixel(scene, settings).x;
  settings.lightSamples = 1024;
  const float more = centrePixel(scene, settings).x;
  EXPECT_NEAR(many, more, 0.01f * more);  // stratified: converged to 1 %
  settings.lightSamples = 256;
  EXPECT_EQ(centrePixel(scene, settings).x, many);  // deterministic
}

TEST(TriangularLight, DirectionalModelHasNoFallOff) {
  Scene scene = quadScene(plainMaterial());
  scene.materials[0].ambient = Color(0.0f);
  scene.lights.of<TriangularLight>().push_back(lightAboveCentre(100.0f));
  RenderSettings settings;
  settings.triangularLightModel = TriangularLightModel::Directional;
  EXPECT_NEAR(centrePixel(scene, settings).x, 100.0f, 1e-4f);  // E = I, l = -n_L = n
}

TEST(TriangularLight, DirectionalShadowRayIsUnbounded) {
  Scene scene = quadScene(plainMaterial());
  scene.materials[0].ambient = Color(0.0f);
  scene.lights.of<TriangularLight>().push_back(lightAboveCentre(100.0f));
  addTriangle(scene, {-1, -1, 50}, {1, -1, 50}, {0, 1, 50}, 0);  // far behind the light, on the way
  RenderSettings settings;
  settings.triangularLightModel = TriangularLightModel::Directional;
  EXPECT_EQ(centrePixel(scene, settings).x, 0.0f);
}

// Two facing mirrors: the camera ray bounces between them until the depth runs out.
Scene facingMirrors(int depth) {
  Material mirror = plainMaterial();
  mirror.mirror = Color(0.5f);
  Scene scene = quadScene(mirror);
  scene.maxRayDepth = depth;
  scene.background = Color(255.0f);
  scene.ambientLight = Color(10.0f);
  addTriangle(scene, {-10, -10, 2}, {0, 10, 2}, {10, -10, 2}, 0);  // faces -z, behind the camera
  return scene;
}

TEST(Mirror, RecursionStopsAtMaxDepth) {
  for (int depth : {0, 1, 2, 7}) {
    RayCounts counts;
    const Color c = centrePixel(facingMirrors(depth), {}, &counts);
    EXPECT_EQ(counts.reflection, static_cast<std::uint64_t>(depth)) << "depth " << depth;
    // Each bounce adds ambient 10 scaled by 0.5^k: 10 (1 + 0.5 + ... + 0.5^depth).
    EXPECT_NEAR(c.x, 10.0 * (2.0 - std::pow(0.5, depth)), 1e-3) << "depth " << depth;
  }
}

TEST(Mirror, TheDeepestAcceptedDepthCannotExhaustTheStack) {
  // Depth 20 000 between facing mirrors once overflowed the stack (SIGSEGV): paths are now followed in a loop.
  // The largest depth any scene, option or script may ask for, on a worker thread with a small stack.
  RayCounts counts;
  Color c;
  std::thread worker([&] { c = centrePixel(facingMirrors(kMaxRayDepth), {}, &counts); });
  worker.join();
  EXPECT_EQ(counts.reflection, static_cast<std::uint64_t>(kMaxRayDepth));
  EXPECT_NEAR(c.x, 20.0, 1e-3);  // 10 (1 + 0.5 + 0.25 + ...)
}

TEST(Mirror, DepthOverrideWins) {
  RenderSettings settings;
  Scene scene = facingMirrors(9);
  const KnobAssignment depth{&depthKnob(), 3};  // --depth 3, written into the scene's parameters
  applyKnobs({&depth, 1}, {&scene.parameters(), &settings});
  RayCounts counts;
  centrePixel(scene, settings, &counts);
  EXPECT_EQ(counts.reflection, 3u);
}

TEST(Mirror, AMissAddsNothingNotTheBackground) {
  Material mirror = plainMaterial();
  mirror.mirror = Color(1.0f);
  Scene scene = quadScene(mirror);
  scene.maxRayDepth = 5;
  scene.background = Color(200.0f);
  scene.ambientLight = Color(10.0f);
  EXPECT_NEAR(centrePixel(scene).x, 10.0f, 1e-4f);
}

TEST(Quantize, ClampsAndRoundsToNearest) {
  EXPECT_EQ(quantizeChannel(-3.0f), 0);
  EXPECT_EQ(quantizeChannel(0.49f), 0);
  EXPECT_EQ(quantizeChannel(0.5f), 1);
  EXPECT_EQ(quantizeChannel(254.5f), 255);
  EXPECT_EQ(quantizeChannel(1e30f), 255);
  EXPECT_EQ(quantizeChannel(INFINITY), 255);
  EXPECT_EQ(quantizeChannel(NAN), 0);
}

Scene busyScene() {
  Scene scene;
  scene.camera = frontCamera(61);
  scene.camera.width = 67;
  scene.maxRayDepth = 3;
  scene.ambientLight = Color(20.0f);
  Material a = plainMaterial("a");
  a.specular = Color(0.5f);
  a.phongExponent = 20;
  Material b = plainMaterial("b");
  b.mirror = Color(0.6f);
  scene.materials = {a, b};
  addQuadFacingZ(scene, -3, -3, 3, 3, -4, 1);
  addTriangle(scene, {-1, -1, -2}, {1, -1, -2.5}, {0, 1, -3}, 0);
  addTriangle(scene, {0.2, -0.8, -1.5}, {0.9, -0.6, -1.6}, {0.5, 0.3, -1.8}, 0);
  scene.lights.of<PointLight>().push_back({"p", {1, 2, 0}, Color(300.0f, 200.0f, 100.0f)});
  scene.lights.of<TriangularLight>().push_back(lightAboveCentre(200.0f));
  return scene;
}

TEST(Threads, ImageIsBitIdenticalForAnyThreadCount) {
  const Scene scene = busyScene();
  RenderSettings settings;
  settings.lightSamples = 9;
  auto geometry = prepareGeometry(scene, settings.accel, BvhBuild::Interactive);
  const Tracer tracer(scene, *geometry->accel, geometry->shading, settings);
  Image reference;
  for (int threads : {1, 2, 3, 8}) {
    ThreadPool pool(threads);
    Image image;
    FrameStats stats;
    ASSERT_TRUE(renderFrame(tracer, scene.camera.width, scene.camera.height, pool, image, stats));
    if (threads == 1) {
      reference = image;
      continue;
    }
    EXPECT_EQ(image.rgb, reference.rgb) << threads << " threads";
  }
}

// A scene big enough that the packet BVH builds the halves under its top node on threads of their own
// (renderer/packet_bvh_accel.cpp, Builder): it answers every ray bit for bit as the same BVH built on one thread
// (so the image cannot depend on the machine's cores), and under ThreadSanitizer (this test runs in the tsan preset)
// the halves share nothing. That it answers as Embree does is tests/packet_test.cpp's, whose killeroo_2020 (92 092
// triangles) is built on threads too.
TEST(Threads, APacketBvhBuiltOnSeveralThreadsAnswersAsOneBuiltOnOne) {
  Scene scene = busyScene();
  const int n = 130;  // a bumpy wall of 2 * 130 * 130 = 33 800 triangles behind the busy scene
  const auto at = [&](int i, int j) {
    const double x = -4.0 + 8.0 * i / n, y = -4.0 + 8.0 * j / n;
    return glm::dvec3(x, y, -4.5 + 0.2 * std::sin(3.0 * x) * std::cos(2.0 * y));
  };
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      addTriangle(scene, at(i, j), at(i + 1, j), at(i + 1, j + 1), 0);
      addTriangle(scene, at(i, j), at(i + 1, j + 1), at(i, j + 1), 0);
    }
  ASSERT_GE(scene.triangles.size(), 32768u);  // the builder's kParallelMin: the top node's halves on two threads
  // Leaves of one triangle, and of several as a lean scene's (whose nodes do not fill the right half's fixed start).
  for (const std::size_t leaves : {std::size_t{1}, kLeanLeafTriangles}) {
    SCOPED_TRACE("leaves of up to " + std::to_string(leaves));
    const std::unique_ptr<Accel> one = makePacketBvhAccel(scene, glm::dvec3(0.0), 1, leaves);
    const std::unique_ptr<Accel> several = makePacketBvhAccel(scene, glm::dvec3(0.0), 4, leaves);
    const glm::dvec3 origin = scene.camera.position;
    // Rays from the camera through a 200 x 200 grid over the wall, and from each hit toward a light.
    int hits = 0;
    for (int i = 0; i < 200; ++i)
      for (int j = 0; j < 200; ++j) {
        const glm::dvec3 target(-4.2 + 8.4 * i / 199, -4.2 + 8.4 * j / 199, -4.5);
        const Ray ray{origin, glm::normalize(target - origin), 0.0, INFINITY};
        const std::optional<Hit> a = one->closestHit(ray), b = several->closestHit(ray);
        ASSERT_EQ(a.has_value(), b.has_value()) << i << ", " << j;
        if (!a) continue;
        ++hits;
        EXPECT_EQ(a->triangle, b->triangle) << i << ", " << j;
        EXPECT_EQ(a->t, b->t) << i << ", " << j;
        const glm::dvec3 point = ray.origin + a->t * ray.direction, light(1, 2, 0);
        const Ray shadow{point, glm::normalize(light - point), 1e-6, glm::length(light - point)};
        EXPECT_EQ(one->occluded(shadow), several->occluded(shadow)) << i << ", " << j;
      }
    EXPECT_GT(hits, 200 * 200 / 2);
  }
}

TEST(Threads, AStopRaisedBeforeTheRenderCancelsIt) {
  const Scene scene = busyScene();
  auto geometry = prepareGeometry(scene, AccelKind::Embree, BvhBuild::Interactive);
  const Tracer tracer(scene, *geometry->accel, geometry->shading, {});
  ThreadPool pool(2);
  Image image;
  FrameStats stats;
  std::atomic<bool> stop{true};
  EXPECT_FALSE(renderFrame(tracer, scene.camera.width, scene.camera.height, pool, image, stats, &stop));
  EXPECT_EQ(stats.rays.total(), 0u);
}

}  // namespace
}  // namespace rayview

namespace rayview {
namespace {

// A quad covering the right half of an 8x8 view, ambient only: 100 where it is seen, background 0 elsewhere.
Scene halfCoveredScene() {
  Scene scene;
  scene.camera = testing::frontCamera(8);
  Material m = testing::plainMaterial();
  m.ambient = Color(1.0f);
  scene.ambientLight = Color(100.0f);
  scene.materials.push_back(m);
  // The near plane spans [-1, 1] at distance 1 in 8 columns of 0.25: column 5 is [0.25, 0.5], its centre
  // 0.375. The quad's left edge, at 0.3125, covers the centre and 3/4 of the column.
  testing::addQuadFacingZ(scene, 0.3125, -10, 10, 10, -1, 0);
  return scene;
}

Image renderWith(const Scene& scene, const RenderSettings& settings, int threads, RayCounts* rays = nullptr) {
  auto geometry = prepareGeometry(scene, settings.accel, BvhBuild::Interactive);
  const Tracer tracer(scene, *geometry->accel, geometry->shading, settings);
  ThreadPool pool(threads);
  Image image;
  FrameStats stats;
  EXPECT_TRUE(renderFrame(tracer, scene.camera.width, scene.camera.height, pool, image, stats));
  if (rays) *rays = stats.rays;
  return image;
}

// Whether the ray from `eye` along `direction` meets the closed box, in long double (the slab test with no
// widening): what CameraCull::misses must never contradict.
bool rayMeetsBox(const glm::dvec3& eye, const glm::dvec3& direction, const AccelBox& box) {
  long double near = 0.0L, far = std::numeric_limits<long double>::infinity();
  for (int axis = 0; axis < 3; ++axis) {
    const long double o = eye[axis], d = direction[axis], lo = box.lower[axis], hi = box.upper[axis];
    if (d == 0.0L) {
      if (o < lo || o > hi) return false;
      continue;
    }
    long double t0 = (lo - o) / d, t1 = (hi - o) / d;
    if (t0 > t1) std::swap(t0, t1);
    near = std::max(near, t0);
    far = std::min(far, t1);
  }
  return near <= far;
}

// Random cameras (turned, off-centre or mirrored near planes, far from the origin) and boxes placed near the edge
// of a random rectangle of image coordinates: whenever the cull says the rectangle's rays miss the box, none of a
// dense grid of them (edges included) meets it; and it does cull, often, what plainly lies outside.
TEST(CameraCull, NeverCullsARayThatMeetsTheBox) {
  std::mt19937_64 random(477);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  auto vector = [&] { return glm::dvec3(unit(random), unit(random), unit(random)); };
  int culled = 0, culledReachingBehind = 0;
  for (int trial = 0; trial < 4000; ++trial) {
    Camera camera;
    const double far = trial % 4 == 0 ? 1e7 : 1.0;
    camera.position = vector() * far;
    camera.gaze = vector();
    camera.up = vector();
    camera.left = unit(random) - 0.5, camera.right = unit(random) + 0.5;
    camera.bottom = unit(random) - 0.5, camera.top = unit(random) + 0.5;
    if (trial % 3 == 0) std::swap(camera.left, camera.right);
    camera.nearDistance = 0.1 + 2.0 * std::fabs(unit(random));
    camera.width = 64, camera.height = 48;
    if (!cameraProblem(camera).empty()) continue;
    const CameraBasis basis = cameraBasis(camera);
    const glm::dvec3 origin = camera.position + vector();  // the accel's origin, near the camera
    const glm::dvec3 eye = camera.position - origin;
    const double i0 = 64 * std::fabs(unit(random)) - 0.5, j0 = 48 * std::fabs(unit(random)) - 0.5;
    const double i1 = i0 + 4 * std::fabs(unit(random)), j1 = j0 + 4 * std::fabs(unit(random));
    // A point just outside the rectangle's cone (or inside it), at a random depth, and a box around it.
    const double pi = trial % 2 ? i1 + 1e-7 * unit(random) : i0 + 3 * unit(random);
    const double pj = trial % 5 ? j0 + 1e-7 * unit(random) : j1 + 3 * unit(random);
    const glm::dvec3 p = eye + pixelDirection(camera, basis, pi, pj) * (0.5 + 3.0 * std::fabs(unit(random)));
    const double size = trial % 7 == 0 ? 1e-9 : 0.2 * std::fabs(unit(random));
    AccelBox box;
    box.lower = p - size * glm::abs(vector()), box.upper = p + size * glm::abs(vector());
    if (trial % 3 == 1) {  // reaching behind the eye, as a floor under the camera does
      const glm::dvec3 back = p + 10.0 * glm::normalize(camera.gaze) * unit(random) - 20.0 * glm::normalize(camera.gaze);
      box.lower = glm::min(box.lower, back), box.upper = glm::max(box.upper, back);
    }
    if (!CameraCull(camera, basis, eye, {box}).misses(i0, i1, j0, j1)) continue;
    ++culled;
    culledReachingBehind += trial % 3 == 1;
    for (int a = 0; a <= 16; ++a)
      for (int b = 0; b <= 16; ++b) {
        const double i = i0 + (i1 - i0) * a / 16, j = j0 + (j1 - j0) * b / 16;
        ASSERT_FALSE(rayMeetsBox(eye, glm::normalize(pixelDirection(camera, basis, i, j)), box))
            << "trial " << trial << ": culled, yet the ray through (" << i << ", " << j << ") meets the box";
      }
  }
  EXPECT_GT(culled, 400) << "the cull should answer most rectangles that lie off the box";
  EXPECT_GT(culledReachingBehind, 10) << "and boxes that reach behind the eye";
}

TEST(CameraCull, AnswersWhatLiesBehindBesideAndInFront) {
  Camera camera = testing::frontCamera(8);  // at the origin, down -z, the near plane [-1, 1]^2 at 1
  const CameraBasis basis = cameraBasis(camera);
  AccelBox ahead;
  ahead.lower = {-0.1, -0.1, -3.0}, ahead.upper = {0.1, 0.1, -2.0};
  const CameraCull seeing(camera, basis, glm::dvec3(0.0), {ahead});
  EXPECT_FALSE(seeing.misses(3, 4, 3, 4)) << "the centre pixels see it";
  EXPECT_TRUE(seeing.misses(0, 1, 0, 1)) << "a corner does not";
  EXPECT_TRUE(seeing.misses(6, 7, 3, 4)) << "nor the right edge";

  AccelBox behind;
  behind.lower = {-5.0, -5.0, 1.0}, behind.upper = {5.0, 5.0, 2.0};
  EXPECT_TRUE(CameraCull(camera, basis, glm::dvec3(0.0), {behind}).misses(-0.5, 7.5, -0.5, 7.5));
  AccelBox floor;  // under the eye and reaching behind it: seen in the lower half only
  floor.lower = {-5.0, -1.0, -10.0}, floor.upper = {5.0, -1.0, 10.0};
  const CameraCull under(camera, basis, glm::dvec3(0.0), {floor});
  EXPECT_TRUE(under.misses(0, 7, 0, 3)) << "the upper half looks above it";
  EXPECT_FALSE(under.misses(0, 7, 4, 7));
  AccelBox around;  // holding the eye: every ray starts inside it
  around.lower = glm::dvec3(-1.0), around.upper = glm::dvec3(1.0);
  EXPECT_FALSE(CameraCull(camera, basis, glm::dvec3(0.0), {around}).misses(0, 1, 0, 1));
  EXPECT_FALSE(CameraCull(camera, basis, glm::dvec3(0.0), {behind, ahead}).misses(3, 4, 3, 4)) << "any box seen counts";
  EXPECT_TRUE(CameraCull(camera, basis, glm::dvec3(0.0), {}).misses(0, 1, 0, 1)) << "no box: no triangle";
}

// The batched path culls the background; pixel by pixel, nothing is culled: both give the same colours bit for bit
// and count the same camera rays, with one sample and with several, for a small model at the image's side, whose
// box edge lies between pixels of one block.
TEST(CameraCull, BatchedPixelsEqualPixelByPixel) {
  Scene scene;
  scene.camera = testing::frontCamera(16);
  scene.background = Color(0.1f, 0.3f, 0.7f);
  Material m = testing::plainMaterial();
  scene.materials.push_back(m);
  scene.ambientLight = Color(50.0f);
  scene.lights.of<PointLight>().push_back({"1", glm::dvec3(0.0, 0.0, 1.0), Color(500.0f)});
  testing::addTriangle(scene, {0.3, 0.05, -1.0}, {0.6, 0.2, -1.0}, {0.35, 0.4, -1.0}, 0);
  testing::addQuadFacingZ(scene, -2.5, -2.5, -1.0, -1.5, -3.0, 0);  // a second mesh, a box of its own
  for (int samples : {1, 3}) {
    RenderSettings settings;
    settings.pixelSamples = samples;
    auto geometry = prepareGeometry(scene, settings.accel, BvhBuild::Interactive);
    const Tracer tracer(scene, *geometry->accel, geometry->shading, settings);
    std::vector<PixelXY> pixels;
    for (int y = 0; y < 16; ++y)
      for (int x = 0; x < 16; ++x) pixels.push_back({x, y});
    std::vector<Color> batched(pixels.size());
    RayCounts batchedRays, singleRays;
    for (std::size_t at = 0; at < pixels.size(); at += kPixelBatch)
      tracer.tracePixels(pixels.data() + at, kPixelBatch, batched.data() + at, batchedRays);
    int background = 0;
    for (std::size_t n = 0; n < pixels.size(); ++n) {
      const Color single = tracer.tracePixel(pixels[n].x, pixels[n].y, singleRays);
      EXPECT_EQ(batched[n], single) << "pixel " << pixels[n].x << ", " << pixels[n].y << ", " << samples << " samples";
      background += single == scene.background;
    }
    EXPECT_EQ(batchedRays.camera, singleRays.camera);
    EXPECT_EQ(batchedRays.shadow, singleRays.shadow);
    EXPECT_GT(background, 200) << "most of the image is background";
    EXPECT_LT(background, 248) << "both meshes are seen";
  }
}

// Every triangle a ray can hit lies in one of the accel's boxes, for each back-end; meshes far apart get boxes of
// their own, and triangles with a corner that is not finite are left out.
TEST(AccelBoxes, HoldEveryTriangleAndKeepMeshesApart) {
  Scene scene;
  scene.camera = testing::frontCamera(8);
  scene.materials.push_back(testing::plainMaterial());
  std::mt19937 random(3);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (int mesh = 0; mesh < 3; ++mesh) {
    const glm::dvec3 centre(100.0 * mesh, 0.0, -10.0);
    Mesh m{std::to_string(mesh), 0, static_cast<std::uint32_t>(scene.triangles.size()), 0};
    for (int t = 0; t < 300 + 200 * mesh; ++t) {
      const auto first = static_cast<std::uint32_t>(scene.vertices.size());
      for (int c = 0; c < 3; ++c) scene.vertices.push_back(centre + glm::dvec3(unit(random), unit(random), unit(random)));
      scene.triangles.push_back(Triangle{{first, first + 1, first + 2}});
      ++m.triangleCount;
    }
    scene.meshes.push_back(m);
  }
  scene.vertices[0].x = std::numeric_limits<double>::quiet_NaN();  // its triangle is left out
  for (AccelKind kind : {AccelKind::Embree, AccelKind::Packet, AccelKind::Reference}) {
    auto geometry = prepareGeometry(scene, kind, BvhBuild::Interactive);
    const Accel& accel = *geometry->accel;
    const std::vector<AccelBox>& boxes = accel.boxes();
    ASSERT_GE(boxes.size(), 3u);
    EXPECT_LE(boxes.size(), kAccelBoxes + 1);
    for (const AccelBox& box : boxes) EXPECT_LT(box.upper.x - box.lower.x, 10.0) << "a box spans two meshes";
    for (std::size_t t = 1; t < scene.triangles.size(); ++t) {
      bool held = false;
      for (const AccelBox& box : boxes) {
        bool all = true;
        for (std::uint32_t v : scene.triangles[t].vertex) {
          const glm::dvec3 p = scene.vertices[v] - accel.origin();
          all = all && glm::all(glm::greaterThanEqual(p, box.lower)) && glm::all(glm::lessThanEqual(p, box.upper));
        }
        held = held || all;
      }
      EXPECT_TRUE(held) << "triangle " << t << " is in no box";
    }
  }
}

TEST(AntiAliasing, EdgePixelsBlendAndTheImageIsTheSameForAnyThreadCount) {
  const Scene scene = halfCoveredScene();
  RenderSettings one;
  const Image centre = renderWith(scene, one, 1);
  // One sample: the edge pixel's centre is on the quad, so it is all quad.
  EXPECT_EQ(centre.rgb[(3 * 8 + 4) * 3], 0);
  EXPECT_EQ(centre.rgb[(3 * 8 + 5) * 3], 100);

  RenderSettings sixteen;
  sixteen.pixelSamples = 16;
  RayCounts rays;
  const Image smooth = renderWith(scene, sixteen, 1, &rays);
  EXPECT_EQ(rays.camera, 16u * 64u);
  const int edge = smooth.rgb[(3 * 8 + 5) * 3];
  EXPECT_GT(edge, 20) << "the edge pixel blends quad and background";
  EXPECT_LT(edge, 95) << "the edge pixel blends quad and background";
  EXPECT_EQ(smooth.rgb[(3 * 8 + 7) * 3], 100) << "a pixel inside the quad stays exact";
  EXPECT_EQ(smooth.rgb[(3 * 8 + 1) * 3], 0) << "a background pixel stays exact";
  EXPECT_EQ(renderWith(scene, sixteen, 2).rgb, smooth.rgb) << "bit-identical for any thread count";
  EXPECT_EQ(renderWith(scene, sixteen, 3).rgb, smooth.rgb) << "bit-identical for any thread count";
}

}  // namespace
}  // namespace rayview
