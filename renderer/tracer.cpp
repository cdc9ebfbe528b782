#include "rayview/tracer.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/geometric.hpp>

#include "rayview/light_samples.h"
#include "rayview/prepared_scene.h"
#include "rayview/ray_offset.h"

namespace rayview {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

glm::vec3 toFloat(const glm::dvec3& v) { return glm::vec3(v); }

// Shadow rays stop just short of the light: "up to (but not including) it".
double justBefore(double distance) { return distance * (1.0 - 1e-6); }

}  // namespace

ShadingGeometry prepareShadingGeometry(const Scene& scene, const glm::dvec3& origin) {
  ShadingGeometry g;
  g.vertices.reserve(scene.vertices.size());
  for (const glm::dvec3& v : scene.vertices) g.vertices.push_back(v - origin);
  g.faceNormals.reserve(scene.triangles.size());
  for (const Triangle& t : scene.triangles) {
    // Normal from the world positions: exact whatever the origin.
    const glm::dvec3& a = scene.vertices[t.vertex[0]];
    const glm::dvec3 n = glm::cross(scene.vertices[t.vertex[1]] - a, scene.vertices[t.vertex[2]] - a);
    const double length = glm::length(n);
    g.faceNormals.push_back(length > 0.0 ? n / length : glm::dvec3(0.0, 0.0, 1.0));
  }
  return g;
}

std::uint8_t quantizeChannel(float value) {
  if (!(value > 0.0f)) return 0;  // also NaN
  if (value >= 255.0f) return 255;
  return static_cast<std::uint8_t>(std::floor(value + 0.5f));
}

Tracer::Tracer(const Scene& scene, const Accel& accel, const ShadingGeometry& geometry,
               const RenderSettings& settings)
    : Tracer(scene, scene, accel, geometry, settings) {}

Tracer::Tracer(const Scene& scene, const PreparedGeometry& geometry, const RenderSettings& settings)
    : Tracer(scene, *geometry.source, *geometry.accel, geometry.shading, settings) {}

Tracer::Tracer(const Scene& scene, const Scene& meshes, const Accel& accel, const ShadingGeometry& geometry,
               const RenderSettings& settings)
    : scene_(scene), meshes_(meshes), accel_(accel), geometry_(geometry), settings_(settings) {
  maxDepth_ = settings.maxDepthOverride >= 0 ? settings.maxDepthOverride : scene.maxRayDepth;
  basis_ = cameraBasis(scene.camera);
  eyeRelative_ = scene.camera.position - accel.origin();
  for (const PointLight& light : scene.pointLights) pointLightPositions_.push_back(light.position - accel.origin());
  for (const TriangularLight& light : scene.triangularLights) {
    TriangularLightFrame f;
    f.v1 = light.vertex1 - accel.origin();
    f.v2 = light.vertex2 - accel.origin();
    f.v3 = light.vertex3 - accel.origin();
    f.centroid = (light.vertex1 + light.vertex2 + light.vertex3) / 3.0 - accel.origin();
    const glm::dvec3 n = glm::cross(light.vertex1 - light.vertex2, light.vertex1 - light.vertex3);
    const double length = glm::length(n);
    if (!(length > 0.0)) continue;  // a degenerate light emits nothing
    f.normal = n / length;
    f.intensity = light.intensity;
    triangularLights_.push_back(f);
  }
  useTexture_ = meshes.texture.has_value() && !meshes.texture->rgb.empty();
  settings_.lightSamples = std::clamp(settings_.lightSamples, 1, kMaxLightSamples);
}

Color Tracer::tracePixel(int i, int j, RayCounts& counts) const {
  const glm::dvec3 direction = glm::normalize(pixelDirection(scene_.camera, basis_, i, j));
  const Ray ray{eyeRelative_, direction, 0.0, kInfinity};
  const std::uint32_t seed = hash32(static_cast<std::uint32_t>(j) * 0x9E3779B1U + static_cast<std::uint32_t>(i));
  ++counts.camera;
  if (std::optional<Hit> hit = accel_.closestHit(ray)) return shadeHit(ray, *hit, 0, seed, counts);
  return scene_.background;
}

Color Tracer::trace(const Ray& ray, int depth, std::uint32_t pixelSeed, RayCounts& counts) const {
  ++counts.reflection;
  if (std::optional<Hit> hit = accel_.closestHit(ray)) return shadeHit(ray, *hit, depth, pixelSeed, counts);
  return Color(0.0f);  // a reflected ray that hits nothing adds nothing (course reference)
}

Color Tracer::shadeHit(const Ray& ray, const Hit& hit, int depth, std::uint32_t pixelSeed,
                       RayCounts& counts) const {
  const Triangle& triangle = meshes_.triangles[hit.triangle];
  const Material& material = scene_.materials[triangle.material];
  const auto b1 = static_cast<float>(hit.b1), b2 = static_cast<float>(hit.b2);
  const float b0 = 1.0f - b1 - b2;
  const glm::dvec3& a = geometry_.vertices[triangle.vertex[0]];
  // In double from the barycentrics: on the triangle's plane to double rounding, whatever the ray was.
  const glm::dvec3 pExact = a + hit.b1 * (geometry_.vertices[triangle.vertex[1]] - a) +
                            hit.b2 * (geometry_.vertices[triangle.vertex[2]] - a);
  const glm::dvec3& ngExact = geometry_.faceNormals[hit.triangle];
  const glm::vec3 ng = toFloat(ngExact);
  glm::vec3 n = ng;
  if (triangle.hasNormals()) {
    const glm::vec3 interpolated = b0 * meshes_.normals[triangle.normal[0]] + b1 * meshes_.normals[triangle.normal[1]] +
                                   b2 * meshes_.normals[triangle.normal[2]];
    const float length = glm::length(interpolated);
    if (length > 0.0f && std::isfinite(length)) n = interpolated / length;
  }
  const glm::dvec3 dExact = glm::normalize(ray.direction);
  const glm::vec3 toEye = -toFloat(dExact);
  const bool excludeHit = settings_.secondaryRayStart == SecondaryRayStart::ExcludeHitTriangle;
  const bool fixedEpsilon = scene_.shadowRayEpsilon.has_value();
  const double epsilon = fixedEpsilon ? *scene_.shadowRayEpsilon : 0.0;
  // A secondary ray leaving the surface along `direction`.
  auto secondaryRay = [&](const glm::dvec3& direction) {
    if (excludeHit) return Ray{pExact, direction, 0.0, kInfinity, hit.triangle};
    const glm::dvec3 origin = fixedEpsilon ? pExact + epsilon * ngExact : offsetRayOrigin(pExact, eyeRelative_, ngExact, direction);
    return Ray{origin, direction, 0.0, kInfinity};
  };

  Color color = material.ambient * scene_.ambientLight;

  // One light direction's Blinn-Phong terms, before the shadow test.
  auto reflectedLight = [&](const glm::vec3& toLight, const Color& irradiance) {
    const Color diffuse = material.diffuse * irradiance * std::max(0.0f, glm::dot(n, toLight));
    const glm::vec3 h = glm::normalize(toLight + toEye);
    const float specular = std::pow(std::max(0.0f, glm::dot(n, h)), material.phongExponent);
    return diffuse + material.specular * irradiance * specular;
  };
  // Shadow ray from the surface toward `target` (stopping just before it), or along `l` without end.
  auto visible = [&](const glm::dvec3& l, const glm::dvec3* target) {
    Ray shadow = secondaryRay(l);
    if (target) {
      const glm::dvec3 toTarget = *target - shadow.origin;
      const double length = glm::length(toTarget);
      if (!(length > 0.0)) return true;
      shadow.direction = toTarget / length;
      shadow.tFar = justBefore(length);
    }
    ++counts.shadow;
    return !accel_.occluded(shadow);
  };

  for (std::size_t k = 0; k < pointLightPositions_.size(); ++k) {
    const glm::dvec3 toLight = pointLightPositions_[k] - pExact;
    const double distanceSquared = glm::dot(toLight, toLight);
    if (!(distanceSquared > 0.0)) continue;
    const glm::dvec3 l = toLight / std::sqrt(distanceSquared);
    const Color contribution =
        reflectedLight(toFloat(l), scene_.pointLights[k].intensity / static_cast<float>(distanceSquared));
    if (contribution == Color(0.0f)) continue;  // no shadow ray for light that would add nothing
    if (visible(l, &pointLightPositions_[k])) color += contribution;
  }

  for (const TriangularLightFrame& light : triangularLights_) {
    if (settings_.triangularLightModel == TriangularLightModel::Directional) {
      const glm::dvec3 l = -light.normal;
      const Color contribution = reflectedLight(toFloat(l), light.intensity);
      if (contribution != Color(0.0f) && visible(l, nullptr)) color += contribution;
      continue;
    }
    const int samples = settings_.lightSamples;
    const Color perSample = light.intensity / static_cast<float>(samples);
    for (int s = 0; s < samples; ++s) {
      const glm::vec2 w = triangleSample(s, samples, pixelSeed);
      const glm::dvec3 y = samples == 1 ? light.centroid
                                        : light.v1 + double(w.x) * (light.v2 - light.v1) + double(w.y) * (light.v3 - light.v1);
      const glm::dvec3 toLight = y - pExact;
      const double distanceSquared = glm::dot(toLight, toLight);
      if (!(distanceSquared > 0.0)) continue;
      const glm::dvec3 l = toLight / std::sqrt(distanceSquared);
      const double cosine = glm::dot(light.normal, -l);  // n_L . omega, omega from the light to x
      if (!(cosine > 0.0)) continue;
      const Color contribution = reflectedLight(toFloat(l), perSample * static_cast<float>(cosine / distanceSquared));
      if (contribution == Color(0.0f)) continue;
      if (visible(l, &y)) color += contribution;
    }
  }

  if (material.isMirror() && depth < maxDepth_) {
    const glm::dvec3 nExact(n);
    const glm::dvec3 r = glm::normalize(dExact - 2.0 * glm::dot(dExact, nExact) * nExact);
    const Ray reflected = secondaryRay(r);
    color += material.mirror * trace(reflected, depth + 1, pixelSeed, counts);
  }

  if (useTexture_ && material.textureFactor != 0.0f && triangle.hasTexCoords()) {
    const float tf = material.textureFactor;
    color = tf * sampleTexture(triangle, hit) + (1.0f - tf) * color;
  }
  return color;
}

// Texture lookup: uv interpolated from the face's <texturedata> entries; u to the right, v up (OBJ
// convention: v = 0 is the bottom row of the image); repeat wrap; nearest texel.
Color Tracer::sampleTexture(const Triangle& triangle, const Hit& hit) const {
  const Texture& texture = *meshes_.texture;
  const auto b1 = static_cast<float>(hit.b1), b2 = static_cast<float>(hit.b2);
  const float b0 = 1.0f - b1 - b2;
  const glm::vec2 uv = b0 * meshes_.texCoords[triangle.texCoord[0]] + b1 * meshes_.texCoords[triangle.texCoord[1]] +
                       b2 * meshes_.texCoords[triangle.texCoord[2]];
  if (!std::isfinite(uv.x) || !std::isfinite(uv.y)) return Color(0.0f);
  const float u = uv.x - std::floor(uv.x);
  const float v = uv.y - std::floor(uv.y);
  const int x = std::min(static_cast<int>(u * texture.width), texture.width - 1);
  const int y = std::min(static_cast<int>((1.0f - v) * texture.height), texture.height - 1);
  const std::uint8_t* texel = &texture.rgb[(static_cast<std::size_t>(y) * texture.width + x) * 3];
  return Color(texel[0], texel[1], texel[2]);
}

}  // namespace rayview
