#pragma once
// Scenes and a checked renderer for the numerical-robustness tests and the pictures in docs/numerics.md.

#include <cstdint>

#include "rayview/image.h"
#include "rayview/render_settings.h"
#include "rayview/scene.h"
#include "rayview/tracer.h"

namespace rayview::testing {

// A render through the real path (prepareGeometry, Tracer) that also inspects the unclamped radiance.
struct CheckedRender {
  Image image;
  RayCounts rays;
  long nonFinitePixels = 0;  // pixels whose unclamped radiance has a NaN or infinite channel
  double ms = 0.0;
};

// Renders on a shared pool of two threads, with the accelerator relative to the camera (prepareGeometry).
CheckedRender renderChecked(const Scene& scene, AccelKind accel, const RenderSettings& settings = {});
// Same with the accelerator and shading geometry relative to `origin` instead: the docs use the world
// origin to show what camera-relative coordinates prevent.
CheckedRender renderCheckedWithOrigin(const Scene& scene, AccelKind accel, const glm::dvec3& origin,
                                      const RenderSettings& settings = {});

// The grazing-light scene: a tessellated, tilted square plane (half-size `scale`, n x n quads, matte:
// ka = ks = 0, kd = 1, no ambient light) seen obliquely from above, and one point light far away
// (100 x scale) at `elevationDegrees` above the plane, bright enough for the lit plane to read ~150.
// Every pixel sees the plane; none can be in shadow.
struct GrazingLightScene {
  Scene scene;
  glm::dvec3 planeCentre{0.0};
  glm::dvec3 planeNormal{0.0};
};
GrazingLightScene grazingLightScene(double scale, double elevationDegrees, int pixels, int n = 16);

// Radiance the grazing-light scene must show at pixel (i, j): kd I max(0, n.l) / d^2, worked out in
// double at the exact ray-plane intersection. Negative when the pixel's ray misses the plane.
double expectedGrazingRadiance(const GrazingLightScene& s, int i, int j);

// Two parallel mirrors (km = 1) facing each other 2 units apart, 200 units wide, the camera between them
// looking at one with a narrow view: every camera ray bounces until the depth limit.
Scene facingMirrorsScene(int maxDepth, int pixels);

}  // namespace rayview::testing
