#pragma once
// The one home of the offsets that keep secondary rays off the surface they start from (SPEC section 6).

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

namespace rayview {

// Secondary rays start this far off the surface, relative to the magnitude of the coordinates involved
// (hit point and triangle vertices, all relative to the camera). A float carries ~6e-8 relative precision
// and a hit point computed from a triangle is off by a few ulps of its largest coordinate: 2^-15 keeps a
// margin of ~250 ulps, so no fixed epsilon breaks at 1e-4 or 1e4 scene scale.
inline constexpr float kRelativeRayOffset = 1.0f / 32768.0f;

// Below this, magnitudes are treated as this (keeps the offset out of float's denormal range).
inline constexpr float kSmallestOffsetScale = 1e-30f;

// Start a secondary ray from hit point `p` on a surface with geometric normal `ng`, on the side that
// `direction` leaves to. `coordinateScale` is the largest |coordinate| of the hit point and its triangle.
inline glm::vec3 offsetRayOrigin(const glm::vec3& p, const glm::vec3& ng, const glm::vec3& direction,
                                 float coordinateScale) {
  const float offset = kRelativeRayOffset * std::max(coordinateScale, kSmallestOffsetScale);
  return glm::dot(ng, direction) >= 0.0f ? p + offset * ng : p - offset * ng;
}

inline float maxAbsComponent(const glm::vec3& a) {
  return std::max(std::fabs(a.x), std::max(std::fabs(a.y), std::fabs(a.z)));
}

}  // namespace rayview
