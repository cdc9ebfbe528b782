#pragma once
// The Whitted integrator (SPEC sections 4-6): ambient + Blinn-Phong with I/d^2, hard shadows, recursive
// mirrors, texture blend, triangular lights. One Tracer per render: it reads the scene and settings and
// never changes them, so any number of threads may call tracePixel() at once.

#include <cstdint>
#include <optional>
#include <vector>

#include "rayview/accel.h"
#include "rayview/camera_cull.h"
#include "rayview/camera_rays.h"
#include "rayview/metal_rough.h"
#include "rayview/render_settings.h"
#include "rayview/scene.h"

namespace rayview {

// Rays traced, by kind.
struct RayCounts {
  std::uint64_t camera = 0;
  std::uint64_t shadow = 0;
  std::uint64_t reflection = 0;

  std::uint64_t total() const { return camera + shadow + reflection; }
  RayCounts& operator+=(const RayCounts& o) {
    camera += o.camera;
    shadow += o.shadow;
    reflection += o.reflection;
    return *this;
  }
};

// A pixel: column x, row y from the top.
struct PixelXY {
  int x = 0, y = 0;
};

// Geometry relative to the accelerator's origin, computed once per scene load.
// What shading needs beyond the scene's own arrays: the origin the traversal's coordinates are relative to. Hit points
// (the scene's vertices minus it, in double: on the triangle's plane) and face normals (normalize((v2-v1) x (v3-v1)) of
// the world positions, never flipped) are computed per hit from the scene's vertices: the same numbers a stored copy
// held, without 24-96 B per triangle of copies (docs/PERFORMANCE.md, "Memory per triangle").
struct ShadingGeometry {
  glm::dvec3 origin{0.0};
};

ShadingGeometry prepareShadingGeometry(const SceneGeometry& scene, const glm::dvec3& origin);

// Clamp to [0, 255] and round to nearest (halves up); NaN becomes 0. Inline: three per pixel.
inline std::uint8_t quantizeChannel(float value) {
  if (!(value > 0.0f)) return 0;  // also NaN
  if (value >= 255.0f) return 255;
  return static_cast<std::uint8_t>(static_cast<int>(value + 0.5f));  // truncation is floor: the sum is positive
}
// The same with the knob's choice: Truncate clamps and drops the fraction (floor) instead.
inline std::uint8_t quantizeChannel(float value, Quantization quantization) {
  if (quantization == Quantization::Round) return quantizeChannel(value);
  if (!(value > 0.0f)) return 0;
  if (value >= 255.0f) return 255;
  return static_cast<std::uint8_t>(static_cast<int>(value));
}

struct PreparedGeometry;
struct LitPoint;
struct SecondaryStart;

class Tracer {
 public:
  // Camera, lights, materials and depth from `parameters`; triangles, normals, texture coordinates and the
  // texture from the geometry, which may have been prepared from another copy of the scene: an edit makes a
  // new SceneParameters and never copies the meshes.
  Tracer(const SceneParameters& parameters, const PreparedGeometry& geometry, const RenderSettings& settings);
  // Everything from `scene`, which must be the scene `accel` and `shading` were built from.
  Tracer(const Scene& scene, const Accel& accel, const ShadingGeometry& shading, const RenderSettings& settings);

  // Radiance (0..255 units, unclamped) of pixel (column i, row j from the top): the mean of
  // RenderSettings::pixelSamples stratified camera rays, or the centre's ray for 1.
  Color tracePixel(int i, int j, RayCounts& counts) const;
  // Sample k (0 <= k < pixelSamples()) of pixel (i, j): tracePixel is (traceSample(0) + traceSample(1) + ...) /
  // pixelSamples(), summed in that order in float, so a running sum over passes ends bit-identical to it.
  Color traceSample(int i, int j, int k, RayCounts& counts) const;
  int pixelSamples() const;
  Quantization quantization() const { return settings_.quantization; }
  // out[n] = tracePixel(pixels[n]) (traceSample(pixels[n], k)) for n < count, bit for bit: the camera rays of
  // up to kRayPacket pixels (best a 4x4 block) traverse the scene as one packet.
  void tracePixels(const PixelXY* pixels, int count, Color* out, RayCounts& counts) const;
  void traceSamples(const PixelXY* pixels, int count, int k, Color* out, RayCounts& counts) const;

  int maxDepth() const { return parameters_.maxRayDepth; }

 private:
  // What one surface hit along a mirror path adds: its own light, and how much of the next hit it passes on.
  struct PathVertex;
  // Where shadeHit's shadow rays go: cast at once (one ray's path) or queued for packets (a block's paths).
  struct ImmediateShadows;
  struct QueuedShadows;

  Tracer(const SceneParameters& parameters, const SceneGeometry& meshes, const Accel& accel,
         const ShadingGeometry& shading, const RenderSettings& settings);
  Color traceCameraRay(const Ray& ray, std::uint32_t seed, RayCounts& counts) const;
  // Rays are written field by field into their place: returned by value and copied, a fresh Ray is read with wide
  // loads of narrow stores, which miss store forwarding (half of traceSamples' time).
  void cameraRay(double i, double j, Ray& ray) const;
  // The same through a pixel's centre, from the image's column and row parts (pixelDirection's divisions once).
  void cameraRay(int i, int j, Ray& ray) const;
  // Both: the camera ray along `direction` (not normalised), written field by field.
  void setCameraRay(const glm::dvec3& direction, Ray& ray) const;
  // The camera ray of sample k of pixel (i, j) and the seed of its light samples.
  void sampleRay(int i, int j, int k, std::uint32_t& seed, Ray& ray) const;
  // Whether every camera ray of these pixels' samples passes beside the scene (CameraCull): their colour is the
  // background, as traced.
  bool cameraMisses(const PixelXY* pixels, int count) const;
  // The colours of `count` <= kRayPacket camera rays traced together.
  void traceCameraRays(const Ray* rays, const std::uint32_t* seeds, int count, Color* out, RayCounts& counts) const;
  Color tracePath(const Ray& cameraRay, const Hit& firstHit, std::uint32_t pixelSeed, RayCounts& counts) const;
  // The colour a path has at its vertex of depth `firstDepth`, hit by `firstRay` at `firstHit`: the path
  // followed from there to its end, one ray at a time.
  Color followPath(const Ray& firstRay, const Hit& firstHit, int firstDepth, std::uint32_t pixelSeed,
                   RayCounts& counts) const;
  // The paths of up to kRayPacket camera rays, depth by depth: each depth's shadow rays and mirror rays in packets.
  void tracePaths(const Ray* cameraRays, const std::optional<Hit>* firstHits, const std::uint32_t* pixelSeeds,
                  int count, Color* out, RayCounts& counts) const;
  // The hit's own light (ambient, lights, shadows) into `v`; when the path goes on, sets `mirrorRay` and v's weight
  // of the next hit. Each light direction that adds something goes to `shadows` with its shadow ray, which decides
  // whether it counts. With `lit` set, the lights are left out and the hit as they see it goes to `lit`
  // (shadePointLights, later).
  template <class Shadows>
  void shadeHit(const Ray& ray, const Hit& hit, int depth, std::uint32_t pixelSeed, RayCounts& counts,
                Shadows& shadows, PathVertex& v, Ray& mirrorRay, LitPoint* lit = nullptr) const;
  // The point lights' light directions at `count` hits (a block's, point_light_lanes.h), four hits at a time.
  void shadePointLights(const LitPoint* points, int count, RayCounts& counts, QueuedShadows& shadows) const;
  SecondaryStart secondaryStart() const;
  // The material's texture at the hit, when it has one to show, blended into `v` by its texture factor.
  void applyTexture(const Material& material, const FaceAttributes& attributes, const Hit& hit, PathVertex& v) const;
  Color sampleTexture(const Texture& texture, const FaceAttributes& face, const Hit& hit) const;
  // The Phong terms at the hit: the material's, or where its metallic-roughness map applies, the map's at the texel.
  PhongTerms termsAt(const Material& material, const FaceAttributes& attributes, const Hit& hit) const;
  // The hit's colour before any light: the ambient term and the emission. The vertex colour, where the scene has
  // them, multiplies the ambient and diffuse terms of `terms`.
  Color unlitColor(const Material& material, const FaceAttributes& attributes, const Hit& hit, PhongTerms& terms) const;
  Color vertexColorAt(const Hit& hit) const;
  // The light a material gives off at the hit: its emission, times its emission map's texel when it has one.
  Color emissionAt(const Material& material, const FaceAttributes& attributes, const Hit& hit) const;
  // SceneGeometry::materialOf, on arrays of the mesh ranges' starts and materials alone: once per hit.
  const Material& materialOf(std::uint32_t triangle) const;

  const SceneParameters& parameters_;  // camera, lights, materials, depth
  const SceneGeometry& meshes_;        // triangles, normals, texture coordinates, texture
  const Accel& accel_;
  const ShadingGeometry& shading_;
  RenderSettings settings_;
  CameraBasis basis_;
  std::vector<glm::dvec3> columnParts_, rowParts_;  // pixelColumnPart / pixelRowPart of each pixel centre
  glm::dvec3 eyeRelative_{0.0};
  std::optional<CameraCull> cull_;  // set once the eye is known
  SceneLights::Prepared lights_;  // by type, in the order of light_types.h
  bool pointLightsOnly_ = false;  // so a block's hits are lit four at a time (shadePointLights)
  std::vector<const Texture*> textures_;  // per material: SceneGeometry::textureOf, once per render
  std::vector<const Texture*> emissionMaps_;  // per material: its <emissionimage>, or null
  std::vector<const Texture*> metalRoughMaps_;  // per material: its <metallicroughnessimage>, or null
  bool anyMetalRough_ = false;                  // so the handout's scenes never look one up
  std::vector<std::uint32_t> meshStarts_;     // each mesh's first triangle, in order
  std::vector<std::uint32_t> meshMaterials_;  // and its material
};

}  // namespace rayview
