// One light type, one place, so that adding a type needs no edit here: the light list and the field tables drive the
// loader, the writer, scripts and the tracer's preparation, so every test here loops over the list and the tables. A
// light type added to SceneLights is covered without a line changed here.
#include "rayview/light_types.h"

#include <array>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "rayview/diagnostics.h"
#include "rayview/render_settings.h"
#include "rayview/scene_loader.h"
#include "rayview/scene_writer.h"
#include "support/image_compare.h"

namespace rayview {
namespace {

// A light type of the test's own: two points and an intensity, which emits only when its points differ.
struct BeamShading;
struct BeamLight {
  std::string id;
  glm::dvec3 from{0.0}, to{0.0};
  Color intensity{0.0f};
  bool operator==(const BeamLight&) const = default;

  static constexpr LightTypeName kType{"beamlight", "beam light", "beam lights", "Beam light"};
  static constexpr auto fields() {
    using F = LightField<BeamLight>;
    return std::array{F::at("from", "From", &BeamLight::from), F::at("to", "To", &BeamLight::to),
                      F::radiance("intensity", "Intensity", &BeamLight::intensity)};
  }
  using Shading = BeamShading;
};
struct BeamShading {
  glm::dvec3 from;
  static std::optional<BeamShading> prepare(const BeamLight& light, const glm::dvec3& origin, const RenderSettings&) {
    if (light.from == light.to) return std::nullopt;
    return BeamShading{light.from - origin};
  }
};

TEST(LightLists, HoldOneListPerTypeInListOrderAndCompareByValue) {
  LightLists<PointLight, BeamLight> a;
  EXPECT_TRUE(a.empty());
  a.of<PointLight>().push_back({"p", {1, 2, 3}, Color(4.0f)});
  a.of<BeamLight>().push_back({"b1", {0, 0, 0}, {0, 0, 1}, Color(1.0f)});
  a.of<BeamLight>().push_back({"b2", {5, 5, 5}, {5, 5, 5}, Color(1.0f)});  // emits nothing
  EXPECT_EQ(a.count(), 3u);
  std::vector<std::string> seen;
  a.forEachType([&](const auto& list) {
    for (const auto& light : list) seen.push_back(std::string(LightOf<decltype(list)>::kType.noun) + " " + light.id);
  });
  EXPECT_EQ(seen, (std::vector<std::string>{"point light p", "beam light b1", "beam light b2"}));

  LightLists<PointLight, BeamLight> b = a;
  EXPECT_TRUE(a == b);
  b.of<BeamLight>()[0].to.z = 2.0;  // any field of any type takes part in ==
  EXPECT_FALSE(a == b);

  // Preparation asks each type; a light its type says emits nothing is left out.
  const auto prepared = a.prepare(glm::dvec3(1.0, 0.0, 0.0), RenderSettings{});
  ASSERT_EQ(std::get<std::vector<PointLightShading>>(prepared).size(), 1u);
  EXPECT_EQ(std::get<std::vector<PointLightShading>>(prepared)[0].position, glm::dvec3(0, 2, 3));
  ASSERT_EQ(std::get<std::vector<BeamShading>>(prepared).size(), 1u);
  EXPECT_EQ(std::get<std::vector<BeamShading>>(prepared)[0].from, glm::dvec3(-1, 0, 0));
}

// "<name>" or "</name>" (built by append: GCC 12 warns, falsely, on "<" + std::string(...)).
std::string tag(std::string_view name, bool closing = false) {
  std::string text(closing ? "</" : "<");
  return text.append(name).append(">");
}

// A scene with one light of every type, each field a value of its own.
std::string sceneWithEveryLightType(SceneLights& lights) {
  double next = 1.0;
  lights.forEachType([&](auto& list) {
    using Light = LightOf<decltype(list)>;
    Light light;
    light.id = std::string(Light::kType.element) + "-1";
    for (const auto& field : Light::fields()) {
      if (field.point) light.*field.point = glm::dvec3(next, next + 0.25, next + 0.5);
      else light.*field.intensity = Color(static_cast<float>(next * 100.0));
      next += 1.0;
    }
    list.push_back(light);
  });
  std::string text =
      "<scene><maxraytracedepth>1</maxraytracedepth><background>0 0 0</background>"
      "<camera><position>0 0 5</position><gaze>0 0 -1</gaze><up>0 1 0</up><nearplane>-1 1 -1 1</nearplane>"
      "<neardistance>1</neardistance><imageresolution>8 8</imageresolution></camera>"
      "<lights><ambientlight>1 1 1</ambientlight>";
  lights.forEachType([&](const auto& list) {
    using Light = LightOf<decltype(list)>;
    for (const Light& light : list) {
      text.append("<").append(Light::kType.element).append(" id=\"").append(light.id).append("\">");
      for (const auto& field : Light::fields()) {
        std::ostringstream values;
        values.precision(17);
        if (field.point) values << (light.*field.point).x << " " << (light.*field.point).y << " " << (light.*field.point).z;
        else values << (light.*field.intensity).x << " " << (light.*field.intensity).y << " " << (light.*field.intensity).z;
        text += tag(field.element) + values.str() + tag(field.element, true);
      }
      text += tag(Light::kType.element, true);
    }
  });
  text +=
      "</lights><materials><material id=\"1\"><ambient>1 1 1</ambient><diffuse>1 1 1</diffuse>"
      "<specular>0 0 0</specular><phongexponent>1</phongexponent><mirrorreflectance>0 0 0</mirrorreflectance>"
      "</material></materials><vertexdata>-1 -1 0 1 -1 0 0 1 0</vertexdata>"
      "<objects><mesh id=\"1\"><materialid>1</materialid><faces>1 2 3</faces></mesh></objects></scene>";
  return text;
}

TEST(LightTypes, TheLoaderReadsEveryFieldOfEveryTypeAndTheWriterWritesItBack) {
  SceneLights expected;
  const std::string text = sceneWithEveryLightType(expected);
  const LoadedScene loaded = loadSceneText(text, "lights.xml", ".");
  EXPECT_TRUE(loaded.scene.lights == expected);
  EXPECT_TRUE(loaded.warnings.empty());

  const auto written = testing::testOutputDirectory() / "light_types_roundtrip.xml";
  writeSceneFile(written, loaded.scene);
  const LoadedScene again = loadSceneFile(written);
  EXPECT_TRUE(again.scene.lights == expected);
}

TEST(LightTypes, AMissingOrRepeatedFieldIsNamedWithItsLine) {
  SceneLights lights;
  const std::string text = sceneWithEveryLightType(lights);
  lights.forEachType([&](const auto& list) {
    using Light = LightOf<decltype(list)>;
    for (const auto& field : Light::fields()) {
      const std::string open = tag(field.element);
      std::string lightOpen = tag(Light::kType.element);
      lightOpen.back() = ' ';  // "<pointlight "
      // This type's element of this field: the first after the light's own start tag.
      const std::size_t at = text.find(open, text.find(lightOpen));
      const std::size_t end = text.find(tag(field.element, true), at) + open.size() + 1;
      std::string missing = text;
      missing.erase(at, end - at);
      try {
        loadSceneText(missing, "lights.xml", ".");
        ADD_FAILURE() << "no error without " << open << " in a " << Light::kType.noun;
      } catch (const SceneError& error) {
        EXPECT_NE(std::string(error.what()).find("has no " + open), std::string::npos) << error.what();
      }
      std::string repeated = text;
      repeated.insert(end, text.substr(at, end - at));
      try {
        loadSceneText(repeated, "lights.xml", ".");
        ADD_FAILURE() << "no error for a repeated " << open << " in a " << Light::kType.noun;
      } catch (const SceneError& error) {
        EXPECT_NE(std::string(error.what()).find("duplicate " + open), std::string::npos) << error.what();
      }
    }
  });
}

TEST(LightTypes, ScriptsSetEveryFieldOfEveryTypeByItsName) {
  SceneLights lights;
  sceneWithEveryLightType(lights);
  const std::string names = lightPropertyNames();
  lights.forEachType([&](auto& list) {
    using Light = LightOf<decltype(list)>;
    for (const auto& field : Light::fields()) {
      EXPECT_TRUE(isLightProperty(field.element));
      EXPECT_NE(names.find(field.element), std::string::npos) << names;
      ASSERT_TRUE(setLightValue(lights, list[0].id, field.element, glm::dvec3(-7.0, 8.0, -9.0)));
      if (field.point) EXPECT_EQ(list[0].*field.point, glm::dvec3(-7.0, 8.0, -9.0)) << field.element;
      else EXPECT_EQ(list[0].*field.intensity, Color(-7.0f, 8.0f, -9.0f)) << field.element;
    }
    EXPECT_NE(lightIds(lights).find(std::string(Light::kType.plural) + ": " + list[0].id), std::string::npos);
  });
  EXPECT_FALSE(isLightProperty("colour"));
  EXPECT_FALSE(setLightValue(lights, "no-such-id", "intensity", glm::dvec3(1.0)));
}

}  // namespace
}  // namespace rayview
