// Fuzz target "scene": the scene loader (tolerant or strict) on any text, then a tiny render of what it
// accepted with each traversal back-end. Nothing may crash, hang or touch memory it does not own; the loader's
// two readings (the big blocks as a stream, or all through tinyxml2's DOM) must agree exactly, and so must the
// pixels of the packet BVH and of Embree on a small scene.
//
// Input: byte 0 chooses the options, the rest is the XML text.
//   bit 0: strict mode; bits 1-2: light samples - 1 (1..4); bit 3: directional triangular lights;
//   bit 4: secondary rays start at the hit point (exclude-hit). scripts/fuzz prefixes seeds with 0.
#include <algorithm>
#include <cstring>
#include <string>
#include <vector>

#include "fuzz_input.h"
#include "rayview/accel.h"
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

// What a load gave: the error's text, or the warnings and the scene.
struct Outcome {
  std::string error;
  std::vector<std::string> warnings;
  rayview::LoadedScene loaded;
};

Outcome load(std::string_view text, rayview::LoadOptions options, bool stream) {
  options.streamBlocks = stream;
  Outcome out;
  try {
    out.loaded = rayview::loadSceneText(text, "fuzz.xml", {}, options);
    for (const rayview::Diagnostic& d : out.loaded.warnings) out.warnings.push_back(d.format());
  } catch (const rayview::SceneError& error) {
    if (error.diagnostic().message.empty()) rayview::fuzz::fail("a SceneError without a message");
    out.error = error.what();
  }
  return out;
}

template <class T, class Allocator>
bool sameBits(const std::vector<T, Allocator>& a, const std::vector<T, Allocator>& b) {
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

void expectTheSame(const Outcome& streamed, const Outcome& dom) {
  using rayview::fuzz::fail;
  if (streamed.error != dom.error) fail("the stream and the DOM give different errors");
  if (streamed.warnings != dom.warnings) fail("the stream and the DOM give different warnings");
  const rayview::Scene& a = streamed.loaded.scene;
  const rayview::Scene& b = dom.loaded.scene;
  if (!(a.parameters() == b.parameters())) fail("the stream and the DOM give different parameters");
  if (!sameBits(a.vertices, b.vertices) || !sameBits(a.texCoords, b.texCoords) || !sameBits(a.normals, b.normals))
    fail("the stream and the DOM give different vertices, texture coordinates or normals");
  if (a.triangles.size() != b.triangles.size() || a.meshes.size() != b.meshes.size())
    fail("the stream and the DOM give different triangle or mesh counts");
  if (!sameBits(a.triangles, b.triangles)) fail("the stream and the DOM give different triangles");
  if (a.faceAttributes != b.faceAttributes) fail("the stream and the DOM give different face attributes");
  for (std::size_t i = 0; i < a.meshes.size(); ++i)
    if (a.meshes[i].id != b.meshes[i].id || a.meshes[i].firstTriangle != b.meshes[i].firstTriangle ||
        a.meshes[i].triangleCount != b.meshes[i].triangleCount || a.meshes[i].material != b.meshes[i].material)
      fail("the stream and the DOM give different meshes");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace rayview;
  if (size < 1) return 0;
  const std::uint8_t flags = data[0];
  LoadOptions options;
  options.strict = (flags & 1) != 0;
  options.loadTexture = false;

  const std::string_view text = fuzz::asText(data + 1, size - 1);
  Outcome streamed = load(text, options, true);
  expectTheSame(streamed, load(text, options, false));
  if (!streamed.error.empty()) return 0;
  LoadedScene& loaded = streamed.loaded;
  if (const std::string problem = wholenessProblem(loaded.scene); !problem.empty()) fuzz::fail(problem.c_str());

  Scene& scene = loaded.scene;
  scene.camera.width = std::clamp(scene.camera.width, 1, kMaxPixelsPerSide);
  scene.camera.height = std::clamp(scene.camera.height, 1, kMaxPixelsPerSide);
  scene.maxRayDepth = std::clamp(scene.maxRayDepth, 0, kMaxDepth);
  if (!scene.textureImage.empty()) scene.texture = tinyTexture();

  RenderSettings settings;
  settings.lightSamples = 1 + ((flags >> 1) & 3);
  settings.triangularLightModel = (flags & 8) ? TriangularLightModel::Directional : TriangularLightModel::Area;
  settings.secondaryRayStart = (flags & 16) ? SecondaryRayStart::ExcludeHitTriangle : SecondaryRayStart::Offset;

  // The pixels each back-end gives: Embree asked for (the packet BVH on a small scene), the reference BVH, and
  // Embree itself when the scene is in its range, which must give the packet BVH's pixels bit for bit.
  auto render = [&](const Accel& accel, const ShadingGeometry& shading) {
    const Tracer tracer(scene, accel, shading, settings);
    RayCounts counts;
    std::vector<glm::vec3> pixels;
    for (int j = 0; j < scene.camera.height; ++j)
      for (int i = 0; i < scene.camera.width; ++i) {
        pixels.push_back(tracer.tracePixel(i, j, counts));
        (void)quantizeChannel(pixels.back().x);
      }
    return pixels;
  };
  std::vector<glm::vec3> packetPixels;
  for (const AccelKind kind : {AccelKind::Embree, AccelKind::Reference}) {
    settings.accel = availableAccel(kind);
    const auto geometry = prepareGeometry(scene, settings.accel, BvhBuild::Interactive);
    if (!geometry) fuzz::fail("prepareGeometry returned nothing without being cancelled");
    std::vector<glm::vec3> pixels = render(*geometry->accel, geometry->shading);
    if (geometry->accel->kind() == AccelKind::Packet) packetPixels = std::move(pixels);
  }
  const glm::dvec3 origin = scene.camera.position;
  if (!packetPixels.empty() && availableAccel(AccelKind::Embree) == AccelKind::Embree &&
      embreeRangeProblem(scene, scene.geometry(), origin).empty()) {
    settings.accel = AccelKind::Embree;
    const std::unique_ptr<Accel> embree = buildAccel(scene.geometry(), AccelKind::Embree, origin);
    if (!embree || embree->kind() != AccelKind::Embree) fuzz::fail("Embree was not built for a scene in its range");
    if (!sameBits(render(*embree, prepareShadingGeometry(scene.geometry(), origin)), packetPixels))
      fuzz::fail("the packet BVH and Embree give different pixels");
  }
  return 0;
}
