#include "orbit_camera.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

namespace rayview {
namespace {

// frame() leaves this much room around the bounding sphere.
constexpr double kFrameMargin = 1.02;

bool isUsable(const glm::dvec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z) && glm::length(v) > 0.0; }

// The camera's right and true-up axes (SPEC section 3: u = up x w, v = w x u), tolerant of degenerate input.
void rightAndUp(const Camera& camera, glm::dvec3& u, glm::dvec3& v) {
  const glm::dvec3 w = -glm::normalize(camera.gaze);
  glm::dvec3 right = glm::cross(camera.up, w);
  if (!isUsable(right)) right = glm::cross(glm::dvec3(0, 1, 0), w);
  if (!isUsable(right)) right = glm::cross(glm::dvec3(1, 0, 0), w);
  u = glm::normalize(right);
  v = glm::cross(w, u);
}

}  // namespace

double fittingHalfAngleTangent(const Camera& camera) {
  const double d = camera.nearDistance > 0.0 ? camera.nearDistance : 1.0;
  const double smallestExtent = std::min({-camera.left, camera.right, -camera.bottom, camera.top});
  // An off-axis window (the gaze line outside the near plane's rectangle) fits no cone about the gaze
  // line; half the smaller side is then the best simple guess.
  if (smallestExtent > 0.0) return smallestExtent / d;
  return 0.5 * std::min(std::abs(camera.right - camera.left), std::abs(camera.top - camera.bottom)) / d;
}

void OrbitCamera::setHome(const Camera& fileCamera, const Bounds& bounds) {
  home_ = fileCamera;
  worldUp_ = isUsable(fileCamera.up) ? glm::normalize(fileCamera.up) : glm::dvec3(0, 1, 0);
  sceneRadius_ = bounds.radius() > 0.0 ? bounds.radius() : 1.0;
  homePivot_ = orbitPivot(fileCamera, bounds);
  reset();
}

void OrbitCamera::reset() {
  camera_ = home_;
  pivot_ = homePivot_;
  worldUp_ = isUsable(home_.up) ? glm::normalize(home_.up) : glm::dvec3(0, 1, 0);
}

double OrbitCamera::distance() const { return glm::length(pivot_ - camera_.position); }

double OrbitCamera::minimumDistance() const { return kMinimumDistanceFraction * sceneRadius_; }

void OrbitCamera::setCamera(const Camera& camera) {
  const double keep = distance();
  // A changed up field changes the turntable axis; an up written back by orbit() (orthogonalised) does not.
  if (camera.up != camera_.up && isUsable(camera.up)) worldUp_ = glm::normalize(camera.up);
  camera_ = camera;
  if (isUsable(camera.gaze)) pivot_ = camera.position + glm::normalize(camera.gaze) * keep;
}

void OrbitCamera::lookAtPivot(const glm::dvec3& eye) {
  const glm::dvec3 forward = glm::normalize(pivot_ - eye);
  const glm::dvec3 w = -forward;
  glm::dvec3 u = glm::cross(worldUp_, w);
  if (isUsable(u)) {
    u = glm::normalize(u);
  } else {
    glm::dvec3 v;
    rightAndUp(camera_, u, v);
  }
  camera_.position = eye;
  camera_.gaze = forward;
  camera_.up = glm::cross(w, u);
}

void OrbitCamera::orbit(double yawRadians, double pitchRadians) {
  glm::dvec3 offset = camera_.position - pivot_;
  const double d = glm::length(offset);
  if (!(d > 0.0)) return;
  offset = rotateAbout(offset, worldUp_, yawRadians);

  // Pitch about the right axis, clamped so the eye never passes over a pole of world up.
  const glm::dvec3 direction = offset / d;
  const double elevationFromUp = std::acos(std::clamp(glm::dot(direction, worldUp_), -1.0, 1.0));
  const double target = std::clamp(elevationFromUp - pitchRadians, kPitchLimitRadians,
                                   3.14159265358979323846 - kPitchLimitRadians);
  glm::dvec3 right = glm::cross(worldUp_, direction);
  if (isUsable(right)) {
    right = glm::normalize(right);
    // Rotating about `right` by a negative angle turns the offset toward world up (smaller elevation).
    offset = rotateAbout(offset, right, -(elevationFromUp - target));
  }
  offset *= d / glm::length(offset);  // rotations keep the length; this removes rounding drift
  lookAtPivot(pivot_ + offset);
}

void OrbitCamera::pan(double rightFraction, double upFraction) {
  glm::dvec3 u, v;
  rightAndUp(camera_, u, v);
  const double nearDistance = camera_.nearDistance > 0.0 ? camera_.nearDistance : 1.0;
  const double viewHeight = std::abs(camera_.top - camera_.bottom) / nearDistance * distance();
  const glm::dvec3 delta = (u * rightFraction + v * upFraction) * viewHeight;
  camera_.position += delta;
  pivot_ += delta;
}

void OrbitCamera::dolly(double wheelSteps) {
  const double d = distance();
  if (!(d > 0.0)) return;
  const double wanted = std::max(d * std::pow(kDollyFactorPerWheelStep, wheelSteps), std::min(d, minimumDistance()));
  const glm::dvec3 forward = (pivot_ - camera_.position) / d;
  camera_.position = pivot_ - forward * wanted;
}

void OrbitCamera::dollyToward(const glm::dvec3& target, double wheelSteps) {
  const double d = glm::length(target - camera_.position);
  if (!(d > 0.0) || !isUsable(target - camera_.position)) return dolly(wheelSteps);
  const double wanted = std::max(d * std::pow(kDollyFactorPerWheelStep, wheelSteps), std::min(d, minimumDistance()));
  const double scale = wanted / d;
  // Scaling the eye and the pivot about the target keeps the gaze and the target's place in the image.
  camera_.position = target + (camera_.position - target) * scale;
  pivot_ = target + (pivot_ - target) * scale;
}

void OrbitCamera::setPivot(const glm::dvec3& point) {
  const glm::dvec3 offset = point - camera_.position;
  if (!isUsable(offset) || glm::length(offset) < minimumDistance()) return;
  pivot_ = point;
  lookAtPivot(camera_.position);
}

void OrbitCamera::frame(const Bounds& bounds) {
  if (bounds.empty) return;
  const double d = distance();
  const glm::dvec3 forward = d > 0.0 ? (pivot_ - camera_.position) / d : glm::normalize(camera_.gaze);
  const double radius = bounds.radius() > 0.0 ? bounds.radius() : sceneRadius_;
  sceneRadius_ = radius;
  const double tangent = fittingHalfAngleTangent(camera_);
  const double sine = tangent / std::sqrt(1.0 + tangent * tangent);
  pivot_ = bounds.center();
  lookAtPivot(pivot_ - forward * (radius / sine * kFrameMargin));
}

}  // namespace rayview
