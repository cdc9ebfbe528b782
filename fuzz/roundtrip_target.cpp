// Fuzz target "roundtrip": a scene the loader accepts (tolerant mode), written by the scene writer and read
// back, must load again and give the same parameters. Input: the XML text.
//
// Compared field by field for now: depth, background, ambient light, shadow-ray epsilon, camera, lights and
// materials (the geometry is left to tests/scene_writer_test.cpp).
#include <string>

#include "fuzz_input.h"
#include "rayview/scene_loader.h"
#include "rayview/scene_writer.h"

namespace {

using rayview::fuzz::fail;

template <typename V>
bool same(const V& a, const V& b) {
  for (int i = 0; i < V::length(); ++i)
    if (!(a[i] == b[i])) return false;
  return true;
}

#define EXPECT_SAME(condition) \
  if (!(condition)) fail("round trip changed: " #condition)

void compare(const rayview::Scene& a, const rayview::Scene& b) {
  EXPECT_SAME(a.maxRayDepth == b.maxRayDepth);
  EXPECT_SAME(same(a.background, b.background));
  EXPECT_SAME(same(a.ambientLight, b.ambientLight));
  EXPECT_SAME(a.shadowRayEpsilon == b.shadowRayEpsilon);

  const rayview::Camera &ca = a.camera, &cb = b.camera;
  EXPECT_SAME(same(ca.position, cb.position));
  EXPECT_SAME(same(ca.gaze, cb.gaze));
  EXPECT_SAME(same(ca.up, cb.up));
  EXPECT_SAME(ca.left == cb.left && ca.right == cb.right && ca.bottom == cb.bottom && ca.top == cb.top);
  EXPECT_SAME(ca.nearDistance == cb.nearDistance);
  EXPECT_SAME(ca.width == cb.width && ca.height == cb.height);

  // Every light type, value by value through its field table (light_type.h).
  a.lights.forEachType([&](const auto& listA) {
    using Light = rayview::LightOf<decltype(listA)>;
    const auto& listB = b.lights.of<Light>();
    EXPECT_SAME(listA.size() == listB.size());
    for (std::size_t i = 0; i < listA.size(); ++i) {
      EXPECT_SAME(listA[i].id == listB[i].id);
      for (const auto& field : Light::fields())
        EXPECT_SAME(field.point ? same(listA[i].*field.point, listB[i].*field.point)
                                : same(listA[i].*field.intensity, listB[i].*field.intensity));
    }
  });
  EXPECT_SAME(a.materials.size() == b.materials.size());
  for (std::size_t i = 0; i < a.materials.size(); ++i) {
    const rayview::Material &ma = a.materials[i], &mb = b.materials[i];
    EXPECT_SAME(ma.id == mb.id);
    EXPECT_SAME(same(ma.ambient, mb.ambient) && same(ma.diffuse, mb.diffuse) && same(ma.specular, mb.specular));
    EXPECT_SAME(ma.phongExponent == mb.phongExponent);
    EXPECT_SAME(same(ma.mirror, mb.mirror));
    EXPECT_SAME(ma.textureFactor == mb.textureFactor);
    EXPECT_SAME(ma.twoSided == mb.twoSided);
    // The cutoff is written only with its image (without one it has no effect).
    EXPECT_SAME(ma.alphaImage.empty() == mb.alphaImage.empty());
    EXPECT_SAME(ma.alphaImage.empty() || ma.alphaCutoff == mb.alphaCutoff);
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace rayview;
  LoadOptions options;
  options.loadTexture = false;
  LoadedScene first;
  try {
    first = loadSceneText(fuzz::asText(data, size), "fuzz.xml", {}, options);
  } catch (const SceneError&) {
    return 0;
  }
  const std::string written = sceneToXml(first.scene, first.scene.textureImage);
  LoadedScene second;
  try {
    second = loadSceneText(written, "written.xml", {}, options);
  } catch (const SceneError& error) {
    std::fprintf(stderr, "the written scene does not load: %s\n--- written ---\n%s\n", error.what(), written.c_str());
    fail("round trip: the written scene does not load");
  }
  compare(first.scene, second.scene);
  return 0;
}
