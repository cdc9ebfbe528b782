#pragma once
// How a light type describes itself, so that the loader, the scene writer, the range check, the Lights panel
// and the automation scripts handle every type with one generic loop (so that a new light type touches
// only its own header, its row in light_types.h and its panel, nothing else).
//
// A light type is a struct with
//   std::string id;                    the file's id attribute
//   static constexpr LightTypeName kType;
//   static constexpr auto fields();    its values, in the order the file writes them (a std::array of LightField)
//   using Shading = ...;               the light ready for one render (see point_light.h):
//       static std::optional<Shading> prepare(const Light&, const glm::dvec3& origin, const RenderSettings&);
//       template <class Visit> void illuminate(const glm::dvec3& p, std::uint32_t pixelSeed, Visit&&) const;

#include <string_view>

#include <glm/vec3.hpp>

#include "rayview/color.h"

namespace rayview {

struct LightTypeName {
  std::string_view element;  // the XML element, lower case: "pointlight"
  std::string_view noun;     // in messages: "point light"
  std::string_view plural;   // "point lights"
  std::string_view title;    // in the panel: "Point light"
};

// One value of a light: a point in the scene (a position, a vertex) or an intensity. Exactly one of the two
// member pointers is set.
template <class Light>
struct LightField {
  std::string_view element;  // the XML element and the script property: "vertex1"
  std::string_view label;    // in the panel: "Vertex 1"
  glm::dvec3 Light::*point = nullptr;
  Color Light::*intensity = nullptr;

  static constexpr LightField at(std::string_view element, std::string_view label, glm::dvec3 Light::*member) {
    return {element, label, member, nullptr};
  }
  static constexpr LightField radiance(std::string_view element, std::string_view label, Color Light::*member) {
    return {element, label, nullptr, member};
  }
};

}  // namespace rayview
