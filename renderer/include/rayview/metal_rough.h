#pragma once
// glTF's metallic-roughness on the Whitted model (docs/scene-format.md, "Materials"): one formula for import, which
// writes a material's terms at its map's average texel, and for the tracer, which evaluates them at each texel.

#include <algorithm>

#include "rayview/color.h"
#include "rayview/scene.h"

namespace rayview {

// The Blinn-Phong terms a hit is shaded with.
struct PhongTerms {
  Color ambient{0.0f}, diffuse{0.0f}, specular{0.0f};
  float phongExponent = 1.0f;
  Color mirror{0.0f};
};

inline PhongTerms phongTermsOf(const Material& m) {
  return {m.ambient, m.diffuse, m.specular, m.phongExponent, m.mirror};
}

inline void setPhongTerms(Material& m, const PhongTerms& t) {
  m.ambient = t.ambient;
  m.diffuse = t.diffuse;
  m.specular = t.specular;
  m.phongExponent = t.phongExponent;
  m.mirror = t.mirror;
}

// Base colour `base` (0..1), metallic m and roughness r (0..1): diffuse and ambient base (1 - m); specular
// 0.04 + (base - 0.04) m; mirror base m (1 - r); the exponent 2/a^2 - 2 with a = max(r^2, 0.01), clamped to
// [1, 10000], the Blinn-Phong lobe that matches a microfacet lobe of roughness a.
inline PhongTerms metalRoughTerms(const Color& base, float metallic, float roughness) {
  PhongTerms t;
  const float alpha = std::max(roughness * roughness, 0.01f);
  t.phongExponent = std::clamp(2.0f / (alpha * alpha) - 2.0f, 1.0f, 10000.0f);
  t.specular = Color(0.04f) + (base - Color(0.04f)) * metallic;
  t.diffuse = t.ambient = base * (1.0f - metallic);
  t.mirror = base * (metallic * (1.0f - roughness));
  return t;
}

}  // namespace rayview
