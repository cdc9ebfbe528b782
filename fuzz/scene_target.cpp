// Fuzz target "scene": the scene loader (tolerant or strict) on any text, then a tiny render of what it
// accepted with each traversal back-end. Nothing may crash, hang or touch memory it does not own.
//
// Input: byte 0 chooses the options, the rest is the XML text.
//   bit 0: strict mode; bits 1-2: light samples - 1 (1..4); bit 3: directional triangular lights;
//   bit 4: secondary rays start at the hit point (exclude-hit). scripts/fuzz prefixes seeds with 0.
#include <algorithm>

#include "fuzz_input.h"
#include "rayview/prepared_scene.h"
#include "rayview/scene_loader.h"
#include "rayview/tracer.h"

namespace {

// The render must stay tiny whatever the file asks for: a few pixels, a shallow depth.
constexpr int kMaxPixelsPerSide = 4;
constexpr int kMaxDepth = 3;

// A 3x2 texture instead of reading <textureimage> from disk, so texture sampling is exercised too.
rayview::Texture tinyTexture() {
  rayview::Texture t;
  t.width = 3;
  t.height = 2;
  for (int i = 0; i < t.width * t.height * 3; ++i) t.rgb.push_back(static_cast<std::uint8_t>(i * 37));
  return t;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace rayview;
  if (size < 1) return 0;
  const std::uint8_t flags = data[0];
  LoadOptions options;
  options.strict = (flags & 1) != 0;
  options.loadTexture = false;

  LoadedScene loaded;
  try {
    loaded = loadSceneText(fuzz::asText(data + 1, size - 1), "fuzz.xml", {}, options);
  } catch (const SceneError& error) {
    if (error.diagnostic().message.empty()) fuzz::fail("a SceneError without a message");
    return 0;
  }

  Scene& scene = loaded.scene;
  scene.camera.width = std::clamp(scene.camera.width, 1, kMaxPixelsPerSide);
  scene.camera.height = std::clamp(scene.camera.height, 1, kMaxPixelsPerSide);
  scene.maxRayDepth = std::clamp(scene.maxRayDepth, 0, kMaxDepth);
  if (!scene.textureImage.empty()) scene.texture = tinyTexture();

  RenderSettings settings;
  settings.lightSamples = 1 + ((flags >> 1) & 3);
  settings.triangularLightModel = (flags & 8) ? TriangularLightModel::Directional : TriangularLightModel::Area;
  settings.secondaryRayStart = (flags & 16) ? SecondaryRayStart::ExcludeHitTriangle : SecondaryRayStart::Offset;

  for (const AccelKind kind : {AccelKind::Embree, AccelKind::Reference}) {
    settings.accel = availableAccel(kind);
    const auto geometry = prepareGeometry(scene, settings.accel);
    if (!geometry) fuzz::fail("prepareGeometry returned nothing without being cancelled");
    const Tracer tracer(scene, *geometry, settings);
    RayCounts counts;
    for (int j = 0; j < scene.camera.height; ++j)
      for (int i = 0; i < scene.camera.width; ++i) (void)quantizeChannel(tracer.tracePixel(i, j, counts).x);
  }
  return 0;
}
