#pragma once
// The one home of the offsets that keep secondary rays off the surface they start from (SPEC section 6).

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

namespace rayview {

// Secondary rays start this far off the surface, relative to the magnitude of the hit point (relative to
// the camera). The hit point is computed in double on the exact plane of its triangle, and triangles are
// tested in double (both traversals), so what the offset must cover is the rounding of the ray's float
// origin: half an ulp, ~6e-8 of the magnitude. 2^-15 keeps a margin of ~500, and scales with the scene,
// so no fixed epsilon breaks at 1e-4 or 1e4 scene scale.
inline constexpr double kRelativeRayOffset = 1.0 / 32768.0;

// Below this, magnitudes are treated as this (keeps the offset out of float's denormal range).
inline constexpr double kSmallestOffsetScale = 1e-30;

inline double maxAbsComponent(const glm::dvec3& a) {
  return std::max(std::fabs(a.x), std::max(std::fabs(a.y), std::fabs(a.z)));
}

// Start a secondary ray from hit point `p` on a surface with geometric normal `ng`, on the side that
// `direction` leaves to.
inline glm::dvec3 offsetRayOrigin(const glm::dvec3& p, const glm::dvec3& ng, const glm::vec3& direction) {
  const double offset = kRelativeRayOffset * std::max(maxAbsComponent(p), kSmallestOffsetScale);
  return glm::dot(glm::vec3(ng), direction) >= 0.0f ? p + offset * ng : p - offset * ng;
}

}  // namespace rayview
