#pragma once
// The triangular light (SPEC section 5): its parameters as the file gives them, its two models and their
// settings, and how it lights a surface point. Everything a triangular light is lives here; the tracer only
// asks it for light directions (see Tracer::shadeHit), the knob table (knobs.cpp) lists its settings.

#include <array>
#include <cmath>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "rayview/color.h"
#include "rayview/light_type.h"

namespace rayview {

struct RenderSettings;
struct TriangularLightShading;

// Barycentric weights (of vertex 2 and vertex 3) of sample k of n for the pixel with seed `pixelSeed`
// (renderer/light_samples.h: deterministic, stratified).
glm::vec2 triangleSample(int k, int n, std::uint32_t pixelSeed);

struct TriangularLight {
  std::string id;
  glm::dvec3 vertex1{0.0}, vertex2{0.0}, vertex3{0.0};
  Color intensity{0.0f};

  bool operator==(const TriangularLight&) const = default;

  static constexpr LightTypeName kType{"triangularlight", "triangular light", "triangular lights",
                                       "Triangular light"};
  static constexpr auto fields() {
    using F = LightField<TriangularLight>;
    return std::array{F::at("vertex1", "Vertex 1", &TriangularLight::vertex1),
                      F::at("vertex2", "Vertex 2", &TriangularLight::vertex2),
                      F::at("vertex3", "Vertex 3", &TriangularLight::vertex3),
                      F::radiance("intensity", "Intensity", &TriangularLight::intensity)};
  }
  using Shading = TriangularLightShading;
};

// Area: the light is N point lights spread over the triangle (N = 1: its centroid), each I/N scaled by the
// cosine at the light over d^2. Directional: light arrives along the triangle's normal with intensity I, no
// fall-off (a distant source such as the sun).
enum class TriangularLightModel { Area, Directional };
inline constexpr int kMaxLightSamples = 4096;  // samples per triangular light, area model

std::string_view toString(TriangularLightModel model);
bool parseTriangularLightModel(std::string_view text, TriangularLightModel& out);

// A triangular light ready for one render: vertices relative to the traversal's origin, its normal n_L (the
// side the light leaves) and the model's settings.
struct TriangularLightShading {
  glm::dvec3 v1, v2, v3, centroid, normal;
  Color intensity;
  TriangularLightModel model = TriangularLightModel::Area;
  int samples = 1;

  // Nothing for a degenerate (zero-area) light: it emits nothing. The model and the samples come from the
  // render settings (their knob rows are in knobs.cpp).
  static std::optional<TriangularLightShading> prepare(const TriangularLight& light, const glm::dvec3& origin,
                                                       const RenderSettings& settings);

  // Calls visit(l, irradiance, target) for each light direction at `p`: l the unit direction toward the
  // light, target the sample point a shadow ray must reach, or nullptr for a ray without end (directional).
  template <typename Visit>
  void illuminate(const glm::dvec3& p, std::uint32_t pixelSeed, Visit&& visit) const {
    if (model == TriangularLightModel::Directional) {
      visit(-normal, intensity, static_cast<const glm::dvec3*>(nullptr));
      return;
    }
    const Color perSample = intensity / static_cast<float>(samples);
    for (int s = 0; s < samples; ++s) {
      const glm::vec2 w = triangleSample(s, samples, pixelSeed);
      const glm::dvec3 y = samples == 1 ? centroid : v1 + double(w.x) * (v2 - v1) + double(w.y) * (v3 - v1);
      const glm::dvec3 toLight = y - p;
      const double distanceSquared = glm::dot(toLight, toLight);
      if (!(distanceSquared > 0.0)) continue;
      const glm::dvec3 l = toLight / std::sqrt(distanceSquared);
      const double cosine = glm::dot(normal, -l);  // n_L . omega, omega from the light to x
      if (!(cosine > 0.0)) continue;
      visit(l, perSample * static_cast<float>(cosine / distanceSquared), &y);
    }
  }
};

}  // namespace rayview
