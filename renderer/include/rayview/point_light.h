#pragma once
// The point light (SPEC section 4): its parameters as the file gives them, and how it lights a surface point.
// Everything a point light is lives here (light_type.h says what a light type provides); the tracer only
// asks it for light directions (see Tracer::shadeHit).

#include <array>
#include <cmath>
#include <cstdint>
#include <optional>
#include <string>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "rayview/color.h"
#include "rayview/light_type.h"

namespace rayview {

struct RenderSettings;
struct PointLightShading;

struct PointLight {
  std::string id;
  glm::dvec3 position{0.0};
  Color intensity{0.0f};

  bool operator==(const PointLight&) const = default;

  static constexpr LightTypeName kType{"pointlight", "point light", "point lights", "Point light"};
  static constexpr auto fields() {
    using F = LightField<PointLight>;
    return std::array{F::at("position", "Position", &PointLight::position),
                      F::radiance("intensity", "Intensity", &PointLight::intensity)};
  }
  using Shading = PointLightShading;
};

// A point light ready for one render: its position relative to the traversal's origin.
struct PointLightShading {
  glm::dvec3 position{0.0};
  Color intensity{0.0f};

  static std::optional<PointLightShading> prepare(const PointLight& light, const glm::dvec3& origin,
                                                  const RenderSettings&) {
    return PointLightShading{light.position - origin, light.intensity};
  }

  // Calls visit(l, irradiance, target) once: l the unit direction from `p` to the light, irradiance I/d^2,
  // target the point a shadow ray must reach (it stops just before it).
  template <typename Visit>
  void illuminate(const glm::dvec3& p, std::uint32_t /*pixelSeed*/, Visit&& visit) const {
    const glm::dvec3 toLight = position - p;
    const double distanceSquared = glm::dot(toLight, toLight);
    if (!(distanceSquared > 0.0)) return;
    const glm::dvec3 l = toLight / std::sqrt(distanceSquared);
    visit(l, intensity / static_cast<float>(distanceSquared), &position);
  }
};

}  // namespace rayview
