// The generic light operations of light_types.h: by field name, for every light type.
#include "rayview/light_types.h"

#include <algorithm>

namespace rayview {

bool setLightValue(SceneLights& lights, const std::string& id, std::string_view property, const glm::dvec3& value) {
  bool done = false;
  lights.forEachType([&](auto& list) {
    using Light = LightOf<decltype(list)>;
    for (const auto& field : Light::fields()) {
      if (done || field.element != property) continue;
      for (Light& light : list) {
        if (light.id != id) continue;
        if (field.point) light.*field.point = value;
        else light.*field.intensity = Color(value);
        done = true;
        break;
      }
    }
  });
  return done;
}

namespace {

std::vector<std::string_view> fieldNames() {
  std::vector<std::string_view> names;
  SceneLights().forEachType([&](const auto& list) {
    for (const auto& field : LightOf<decltype(list)>::fields())
      if (std::find(names.begin(), names.end(), field.element) == names.end()) names.push_back(field.element);
  });
  return names;
}

}  // namespace

bool isLightProperty(std::string_view name) {
  const std::vector<std::string_view> names = fieldNames();
  return std::find(names.begin(), names.end(), name) != names.end();
}

std::string lightPropertyNames() {
  const std::vector<std::string_view> names = fieldNames();
  std::string text;
  for (std::string_view name : names) text.append(text.empty() ? "" : "|").append(name);
  return text;
}

std::string lightIds(const SceneLights& lights) {
  std::string text;
  lights.forEachType([&](const auto& list) {
    std::string ids;
    for (const auto& light : list) ids.append(ids.empty() ? "" : ", ").append(light.id);
    text.append(text.empty() ? "" : "; ").append(LightOf<decltype(list)>::kType.plural).append(": ");
    text += ids.empty() ? "none" : ids;
  });
  return text;
}

}  // namespace rayview
