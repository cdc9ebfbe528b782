// Our own scenes (scenes/*.xml, the default one compiled in) are exemplary: they load in strict mode with
// no warning at all, read their texture, and render without a non-finite pixel.
#include <gtest/gtest.h>

#include <cmath>

#include "rayview/prepared_scene.h"
#include "rayview/scene_loader.h"
#include "support/image_compare.h"

namespace rayview {
namespace {

class OwnScene : public ::testing::TestWithParam<std::string> {};

TEST_P(OwnScene, LoadsStrictlyWithoutWarningsAndRenders) {
  LoadOptions strict;
  strict.strict = true;
  const LoadedScene loaded = loadSceneFile(testing::sourceDirectory() / "scenes" / GetParam(), strict);
  for (const Diagnostic& d : loaded.warnings) ADD_FAILURE() << d.format();
  const Scene& scene = loaded.scene;
  EXPECT_FALSE(scene.triangles.empty());
  if (!scene.textureImage.empty()) {
    EXPECT_TRUE(scene.texture.has_value()) << scene.textureImage;
  }
  auto geometry = prepareGeometry(scene, AccelKind::Embree, BvhBuild::Interactive);
  const Tracer tracer(scene, *geometry, RenderSettings{});
  RayCounts counts;
  for (int y = 0; y < scene.camera.height; y += 7)
    for (int x = 0; x < scene.camera.width; x += 7) {
      const Color c = tracer.tracePixel(x, y, counts);
      ASSERT_TRUE(std::isfinite(c.x) && std::isfinite(c.y) && std::isfinite(c.z));
    }
}

INSTANTIATE_TEST_SUITE_P(Scenes, OwnScene,
                         ::testing::Values("default.xml", "triangular_light.xml", "textured_2025.xml"),
                         [](const auto& info) {
                           std::string name = info.param;
                           return name.substr(0, name.find('.'));
                         });

}  // namespace
}  // namespace rayview
