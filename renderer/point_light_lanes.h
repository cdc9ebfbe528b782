#pragma once
// Point lights shading four hits at once. A block's hits are shaded together (Tracer::tracePaths); when a scene's
// lights are all point lights, each light's part of four hits' Blinn-Phong terms and shadow rays is computed in
// vector registers: the square roots and divisions (four per light and hit) run four lanes per instruction.
// Lane for lane the same IEEE operations in the same order as Tracer::shadeHit's scalar code, each rounded on its
// own: the same light directions, contributions and shadow rays bit for bit (Packets.BlocksOfPixelsTraceAsSinglePixels
// compares whole images of every conformance scene against the scalar path).

#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "rayview/accel.h"
#include "rayview/point_light.h"
#include "ray_offset.h"
#include "rayview/scene.h"
#include "simd4.h"
#include "specular_power.h"

namespace rayview {

// Where a hit's secondary rays start (Tracer::secondaryStart, shadeHit's secondaryOrigin): at the hit excluding
// its triangle, at a fixed <shadowrayepsilon> along the normal, or at the robust offset of ray_offset.h.
struct SecondaryStart {
  bool excludeHit = false;
  bool fixedEpsilon = false;
  double epsilon = 0.0;
  glm::dvec3 eye{0.0};  // relative to the traversal's origin
};

// A hit as its lights see it.
struct LitPoint {
  glm::dvec3 p;         // on the triangle's plane, relative to the origin
  glm::dvec3 ng;        // unit geometric normal
  glm::vec3 n;          // shading normal
  glm::vec3 toEye;      // unit direction back along the ray
  Color diffuse;        // the hit's Phong terms (metal_rough.h): the material's, times the vertex colour where
  Color specular;       // the scene has them, or its metallic-roughness map's at the texel
  float phongExponent;
  std::uint32_t triangle;
  int lane;  // the block's lane it belongs to
};

// For each light, then each of points[0 .. count) (count <= 4) it reaches with light that adds something:
// onLight(j, place, contribution, hasRay), place being the light direction's number among that point's (0, 1,
// ...). It returns where the shadow ray that decides whether the contribution counts goes (hasRay is false when
// the light is where that ray would start; the ray is then not written). The ray is written field by field into
// its place: built whole on the stack and copied, its wide loads of narrow stores missed store forwarding (most
// of this function's time).
template <class OnLight>
void shadePointLightsFour(const LitPoint* points, int count, const std::vector<PointLightShading>& lights,
                          const SecondaryStart& start, OnLight&& onLight) {
  auto at = [&](int j) -> const LitPoint& { return points[j < count ? j : 0]; };  // spare lanes repeat the first
  auto gatherD = [&](auto field) { return Double4{field(at(0)), field(at(1)), field(at(2)), field(at(3))}; };
  auto gatherF = [&](auto field) { return Float4{field(at(0)), field(at(1)), field(at(2)), field(at(3))}; };
  Double4 p[3] = {}, ng[3] = {};
  Float4 n[3] = {}, toEye[3] = {}, diffuse[3] = {}, specular[3] = {};
  for (int a = 0; a < 3; ++a) {
    p[a] = gatherD([a](const LitPoint& q) { return q.p[a]; });
    ng[a] = gatherD([a](const LitPoint& q) { return q.ng[a]; });
    n[a] = gatherF([a](const LitPoint& q) { return q.n[a]; });
    toEye[a] = gatherF([a](const LitPoint& q) { return q.toEye[a]; });
    diffuse[a] = gatherF([a](const LitPoint& q) { return q.diffuse[a]; });
    specular[a] = gatherF([a](const LitPoint& q) { return q.specular[a]; });
  }
  const Float4 exponent = gatherF([](const LitPoint& q) { return q.phongExponent; });
  // offsetRayOrigin's offset: kRelativeRayOffset times the hit's largest distance from the eye along an axis.
  const Double4 offset =
      splat4(kRelativeRayOffset) *
      max4(max4(abs4(p[0] - splat4(start.eye.x)),
                max4(abs4(p[1] - splat4(start.eye.y)), abs4(p[2] - splat4(start.eye.z)))),
           splat4(kSmallestOffsetScale));
  const Double4 zeroD{};
  const Float4 zero{};
  int place[4] = {0, 0, 0, 0};
  for (const PointLightShading& light : lights) {
    // PointLightShading::illuminate: l = (position - p) / |position - p|, irradiance I / d^2.
    Double4 toLight[3], l[3];
    for (int a = 0; a < 3; ++a) toLight[a] = splat4(light.position[a]) - p[a];
    const Double4 distanceSquared = (toLight[0] * toLight[0] + toLight[1] * toLight[1]) + toLight[2] * toLight[2];
    const Mask4 reached = distanceSquared > zeroD;
    const Double4 distance = sqrt4(distanceSquared);
    for (int a = 0; a < 3; ++a) l[a] = toLight[a] / distance;
    const Float4 d2 = __builtin_convertvector(distanceSquared, Float4);
    Float4 irradiance[3], lf[3], h[3];
    for (int c = 0; c < 3; ++c) irradiance[c] = splat4(light.intensity[c]) / d2;
    // Blinn-Phong: diffuse * I/d^2 * max(0, n.l) + specular * I/d^2 * max(0, n.h)^e.
    for (int a = 0; a < 3; ++a) lf[a] = __builtin_convertvector(l[a], Float4);
    const Float4 lambert = max4(zero, (n[0] * lf[0] + n[1] * lf[1]) + n[2] * lf[2]);
    for (int a = 0; a < 3; ++a) h[a] = lf[a] + toEye[a];
    const Float4 inverseLength = splat4(1.0f) / sqrt4((h[0] * h[0] + h[1] * h[1]) + h[2] * h[2]);
    for (int a = 0; a < 3; ++a) h[a] = h[a] * inverseLength;
    const Float4 highlight = specularPower4(max4(zero, (n[0] * h[0] + n[1] * h[1]) + n[2] * h[2]), exponent);
    Float4 contribution[3];
    for (int c = 0; c < 3; ++c)
      contribution[c] = (diffuse[c] * irradiance[c]) * lambert + (specular[c] * irradiance[c]) * highlight;
    const Int4 adds = (contribution[0] != zero) | (contribution[1] != zero) | (contribution[2] != zero);
    // The shadow ray, from where secondary rays start to just before the light.
    Double4 origin[3];
    if (start.excludeHit) {
      for (int a = 0; a < 3; ++a) origin[a] = p[a];
    } else if (start.fixedEpsilon) {
      for (int a = 0; a < 3; ++a) origin[a] = p[a] + splat4(start.epsilon) * ng[a];
    } else {
      const Mask4 leaves = ((ng[0] * l[0] + ng[1] * l[1]) + ng[2] * l[2]) >= zeroD;
      for (int a = 0; a < 3; ++a) origin[a] = leaves ? p[a] + offset * ng[a] : p[a] - offset * ng[a];
    }
    Double4 toTarget[3], direction[3];
    for (int a = 0; a < 3; ++a) toTarget[a] = splat4(light.position[a]) - origin[a];
    const Double4 length = sqrt4((toTarget[0] * toTarget[0] + toTarget[1] * toTarget[1]) + toTarget[2] * toTarget[2]);
    for (int a = 0; a < 3; ++a) direction[a] = toTarget[a] / length;
    const Double4 tFar = length * splat4(1.0 - 1e-6);  // just before the light
    for (int j = 0; j < count; ++j) {
      if (!reached[j]) continue;
      const int number = place[j]++;
      if (!adds[j]) continue;  // no shadow ray for light that would add nothing
      const bool hasRay = length[j] > 0.0;
      Ray* shadow = onLight(j, number, Color(contribution[0][j], contribution[1][j], contribution[2][j]), hasRay);
      if (!hasRay) continue;
      for (int a = 0; a < 3; ++a) {
        shadow->origin[a] = origin[a][j];
        shadow->direction[a] = direction[a][j];
      }
      shadow->tNear = 0.0;
      shadow->tFar = tFar[j];
      shadow->excludedTriangle = start.excludeHit ? points[j].triangle : kNoTriangle;
    }
  }
}

}  // namespace rayview
