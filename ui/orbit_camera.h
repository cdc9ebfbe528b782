#pragma once
// Orbit / pan / dolly navigation around a pivot, as pure math on rayview's Camera (no GL, no window).
//
// The camera looks at the pivot once the user starts navigating. Orbiting is turntable style: yaw turns
// about the "world up" (the file camera's up vector), pitch about the camera's right axis, and pitch stops
// short of the poles so that up never becomes parallel to the gaze (SPEC section 3 refuses that camera).
// Only position, gaze and up change; the lens (near plane, near distance, resolution) is left alone.

#include <glm/vec3.hpp>

#include "rayview/scene.h"
#include "rayview/scene_bounds.h"

namespace rayview {

// Bounds, sceneBounds and the orbit pivot's rule are in rayview/scene_bounds.h (turntables use them too).

// Navigation speeds: one pixel of mouse motion in a window `viewportHeight` pixels tall.
inline constexpr double kOrbitRadiansPerViewportHeight = 3.14159265358979323846;  // a full-height drag: 180 degrees
inline constexpr double kDollyFactorPerWheelStep = 0.85;                          // distance multiplier per notch
// Pitch stays this far from straight up or down (radians, about 0.6 degrees).
inline constexpr double kPitchLimitRadians = 0.01;

class OrbitCamera {
 public:
  OrbitCamera() = default;

  // Remembers `fileCamera` for reset() and places the pivot on its gaze line, near the scene's centre.
  void setHome(const Camera& fileCamera, const Bounds& bounds);

  // The camera to render: exactly the file's camera until the user navigates.
  const Camera& camera() const { return camera_; }
  const glm::dvec3& pivot() const { return pivot_; }
  double distance() const;  // from the eye to the pivot

  // Replaces the camera (numeric fields); the pivot stays at the same distance along the new gaze.
  void setCamera(const Camera& camera);

  // Turntable orbit about the pivot: yaw about world up, pitch about the camera's right axis (radians;
  // positive yaw turns the camera to the right around the pivot, positive pitch moves the eye up).
  void orbit(double yawRadians, double pitchRadians);
  // Moves eye and pivot together, in units of the view's height at the pivot distance (1 = one view height).
  void pan(double rightFraction, double upFraction);
  // Moves the eye toward the pivot (positive steps) or away from it; never reaches or crosses the pivot.
  void dolly(double wheelSteps);
  // The same toward `target` (the scene point under the cursor): eye and pivot move toward it together, so the
  // view direction stays and the target stays under the cursor; never reaches it.
  void dollyToward(const glm::dvec3& target, double wheelSteps);
  // Keeps the view direction, centres the pivot on `bounds` and backs off until its sphere fits the view.
  void frame(const Bounds& bounds);
  // Puts the pivot on `point` and turns the camera, from where it is, to look at it.
  void setPivot(const glm::dvec3& point);
  // Back to the file's camera and initial pivot.
  void reset();

 private:
  void lookAtPivot(const glm::dvec3& eye);
  double minimumDistance() const;

  Camera home_;
  glm::dvec3 homePivot_{0.0};
  Camera camera_;
  glm::dvec3 pivot_{0.0, 0.0, -1.0};
  glm::dvec3 worldUp_{0.0, 1.0, 0.0};
  double sceneRadius_ = 1.0;
};

// Tangent of the largest half-angle that a sphere around the gaze axis can have and still fit the view.
double fittingHalfAngleTangent(const Camera& camera);

}  // namespace rayview
