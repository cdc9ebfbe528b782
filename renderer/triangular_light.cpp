#include "rayview/triangular_light.h"

#include "light_samples.h"
#include "rayview/render_settings.h"

namespace rayview {

std::optional<TriangularLightShading> TriangularLightShading::prepare(const TriangularLight& light,
                                                                      const glm::dvec3& origin,
                                                                      const RenderSettings& settings) {
  const glm::dvec3 n = glm::cross(light.vertex1 - light.vertex2, light.vertex1 - light.vertex3);
  const double length = glm::length(n);
  if (!(length > 0.0)) return std::nullopt;
  TriangularLightShading f;
  f.v1 = light.vertex1 - origin;
  f.v2 = light.vertex2 - origin;
  f.v3 = light.vertex3 - origin;
  f.centroid = (light.vertex1 + light.vertex2 + light.vertex3) / 3.0 - origin;
  f.normal = n / length;
  f.intensity = light.intensity;
  f.model = settings.triangularLightModel;
  const int samples = settings.lightSamples;
  f.samples = samples < 1 ? 1 : (samples > kMaxLightSamples ? kMaxLightSamples : samples);
  return f;
}

std::string_view toString(TriangularLightModel model) {
  return model == TriangularLightModel::Area ? "area" : "directional";
}

bool parseTriangularLightModel(std::string_view text, TriangularLightModel& out) {
  if (text == "area") out = TriangularLightModel::Area;
  else if (text == "directional") out = TriangularLightModel::Directional;
  else return false;
  return true;
}

glm::vec2 triangleSample(int k, int n, std::uint32_t pixelSeed) {
  if (n <= 1) return {1.0f / 3.0f, 1.0f / 3.0f};
  const float r1 = static_cast<float>(hash32(pixelSeed) >> 8) * (1.0f / 16777216.0f);
  const float r2 = static_cast<float>(hash32(pixelSeed ^ 0x9e3779b9U) >> 8) * (1.0f / 16777216.0f);
  float a = (static_cast<float>(k) + 0.5f) / static_cast<float>(n) + r1;
  float b = radicalInverseBase2(static_cast<std::uint32_t>(k)) + r2;
  a -= std::floor(a);
  b -= std::floor(b);
  // Area-preserving map of the unit square onto the triangle.
  const float s = std::sqrt(a);
  return {s * (1.0f - b), s * b};
}

}  // namespace rayview
