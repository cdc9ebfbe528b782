#pragma once
// The point light (SPEC section 4): its parameters as the file gives them, and how it lights a surface point.
// Everything a point light is lives here; the tracer only asks it for light directions (see Tracer::shadeHit).

#include <string>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "rayview/color.h"

namespace rayview {

struct PointLight {
  std::string id;
  glm::dvec3 position{0.0};
  Color intensity{0.0f};

  bool operator==(const PointLight&) const = default;
};

// A point light ready for one render: its position relative to the traversal's origin.
struct PointLightShading {
  glm::dvec3 position{0.0};
  Color intensity{0.0f};

  PointLightShading(const PointLight& light, const glm::dvec3& origin)
      : position(light.position - origin), intensity(light.intensity) {}

  // Calls visit(l, irradiance, target) once: l the unit direction from `p` to the light, irradiance I/d^2,
  // target the point a shadow ray must reach (it stops just before it).
  template <typename Visit>
  void illuminate(const glm::dvec3& p, Visit&& visit) const {
    const glm::dvec3 toLight = position - p;
    const double distanceSquared = glm::dot(toLight, toLight);
    if (!(distanceSquared > 0.0)) return;
    const glm::dvec3 l = toLight / std::sqrt(distanceSquared);
    visit(l, intensity / static_cast<float>(distanceSquared), &position);
  }
};

}  // namespace rayview
