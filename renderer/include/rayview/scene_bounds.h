#pragma once
// Where a scene is: its bounds, the viewer's orbit pivot, and the cameras of a turntable around it. Pure math
// on rayview's Camera, shared by the viewer's orbit camera (ui/orbit_camera.h) and `rayview render --turntable`.

#include <glm/vec3.hpp>

#include "rayview/scene.h"

namespace rayview {

// Axis-aligned bounds of what the scene draws (the vertices its triangles use).
struct Bounds {
  glm::dvec3 min{0.0};
  glm::dvec3 max{0.0};
  bool empty = true;

  glm::dvec3 center() const { return (min + max) * 0.5; }
  double radius() const;  // of the bounding sphere through the corners
  void add(const glm::dvec3& p);
};

Bounds sceneBounds(const Scene& scene);

// Below this fraction of the scene's radius the eye would sit on the pivot.
inline constexpr double kMinimumDistanceFraction = 1e-4;

// The viewer's orbit pivot for a file's camera: the point of the gaze line nearest the scene's centre, unless
// that lies behind the eye (then one scene radius along the gaze).
glm::dvec3 orbitPivot(const Camera& camera, const Bounds& bounds);

// Rodrigues' rotation of `v` by `angle` radians about the unit `axis` (right-handed).
glm::dvec3 rotateAbout(const glm::dvec3& v, const glm::dvec3& axis, double angle);

// Frame `frame` of `frames` of a turntable: `camera` turned by 360 degrees * frame / frames about the axis through
// `pivot` along the camera's up vector (the viewer's yaw), the lens unchanged. Frame 0 is `camera` itself.
Camera turntableCamera(const Camera& camera, const glm::dvec3& pivot, int frame, int frames);

}  // namespace rayview
