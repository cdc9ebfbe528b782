#pragma once
// The one home of the offsets that keep secondary rays off the surface they start from (SPEC section 6).

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

namespace rayview {

// Secondary rays start this far off the surface, relative to the magnitude of the hit point (relative to
// the camera). Rays, hit points and triangle tests are all double, so the error to cover is tiny; the
// offset is far larger than it (3e-5 of the distance) because it also covers what float-precision data
// feeds in (barycentrics, normals) and keeps shadow rays clear of grazing neighbours, while staying
// invisible. It scales with the scene, so no fixed epsilon breaks at 1e-4 or 1e4 scene scale.
inline constexpr double kRelativeRayOffset = 1.0 / 32768.0;

// Below this, magnitudes are treated as this (keeps the offset out of float's denormal range).
inline constexpr double kSmallestOffsetScale = 1e-30;

inline double maxAbsComponent(const glm::dvec3& a) {
  return std::max(std::fabs(a.x), std::max(std::fabs(a.y), std::fabs(a.z)));
}

// Start a secondary ray from hit point `p` on a surface with geometric normal `ng`, on the side that
// `direction` leaves to. The offset's scale is the point's distance from the eye (largest component), so
// the same scene seen from the same camera gets the same offsets whatever origin the coordinates use.
inline glm::dvec3 offsetRayOrigin(const glm::dvec3& p, const glm::dvec3& eye, const glm::dvec3& ng,
                                  const glm::dvec3& direction) {
  const double offset = kRelativeRayOffset * std::max(maxAbsComponent(p - eye), kSmallestOffsetScale);
  return glm::dot(ng, direction) >= 0.0 ? p + offset * ng : p - offset * ng;
}

}  // namespace rayview
