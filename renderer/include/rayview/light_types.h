#pragma once
// The one list of light types. Everything else (the scene's light lists, the loader, the writer, the range
// check, the tracer, the Lights panel, scripts) iterates over this list; a new light type is its own header
// (see light_type.h for what it provides) plus one entry in SceneLights below.

#include <cstddef>
#include <string>
#include <string_view>
#include <tuple>
#include <type_traits>
#include <vector>

#include "rayview/point_light.h"
#include "rayview/triangular_light.h"

namespace rayview {

// One vector per light type, in the order of the list (which is also the order of shading, so images do not
// depend on anything but the list).
template <class... Types>
class LightLists {
 public:
  template <class Light>
  std::vector<Light>& of() {
    return std::get<std::vector<Light>>(lists_);
  }
  template <class Light>
  const std::vector<Light>& of() const {
    return std::get<std::vector<Light>>(lists_);
  }

  // visit(std::vector<Light>&) for each type, in list order.
  template <class Visit>
  void forEachType(Visit&& visit) {
    (visit(of<Types>()), ...);
  }
  template <class Visit>
  void forEachType(Visit&& visit) const {
    (visit(of<Types>()), ...);
  }

  std::size_t count() const { return (of<Types>().size() + ... + 0); }
  bool empty() const { return count() == 0; }

  bool operator==(const LightLists&) const = default;

  // Every light ready for one render (Light::Shading), by type; a light that emits nothing is left out.
  using Prepared = std::tuple<std::vector<typename Types::Shading>...>;
  Prepared prepare(const glm::dvec3& origin, const RenderSettings& settings) const {
    Prepared prepared;
    (prepareAll<Types>(std::get<std::vector<typename Types::Shading>>(prepared), origin, settings), ...);
    return prepared;
  }

 private:
  template <class Light>
  void prepareAll(std::vector<typename Light::Shading>& out, const glm::dvec3& origin,
                  const RenderSettings& settings) const {
    for (const Light& light : of<Light>())
      if (auto shading = Light::Shading::prepare(light, origin, settings)) out.push_back(*shading);
  }

  std::tuple<std::vector<Types>...> lists_;
};

// THE list: one entry per light type.
using SceneLights = LightLists<PointLight, TriangularLight>;

// The light type a vector of SceneLights holds.
template <class List>
using LightOf = typename std::remove_cvref_t<List>::value_type;

// Lights of any type by the names of their fields (edits, scripts):
// - sets `property` ("position", "vertex1", "intensity"...) of the first light with `id` whose type has that
//   field, in list order; false when there is none;
bool setLightValue(SceneLights& lights, const std::string& id, std::string_view property, const glm::dvec3& value);
// - every field name there is, "position|intensity|vertex1|...", for usage messages;
std::string lightPropertyNames();
bool isLightProperty(std::string_view name);
// - "point lights: 1, 2; triangular lights: none", for messages.
std::string lightIds(const SceneLights& lights);

}  // namespace rayview
