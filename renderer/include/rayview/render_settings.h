#pragma once
// How to render a scene, as opposed to what the scene is (SceneParameters): the choices a user makes that no
// scene file states. Each field is a row of the knob table (knobs.h), which gives its name, limits and help.

#include <string_view>

#include "rayview/triangular_light.h"

namespace rayview {

// Embree: Embree's BVH (for a scene of up to kPacketBvhTriangles triangles, prepareGeometry builds rayview's packet
// BVH instead: the same answers without Embree's start-up). Reference: the double-precision reference BVH.
// Packet: rayview's packet BVH whatever the scene's size. Embree and Packet answer every ray identically.
enum class AccelKind { Embree, Reference, Packet };
inline constexpr int kAccelKindCount = 3;  // for arrays indexed by AccelKind
static_assert(static_cast<int>(AccelKind::Packet) + 1 == kAccelKindCount);

// Where shadow and mirror rays start. Offset: off the surface (by <shadowrayepsilon> when the scene sets
// it, else by the robust relative offset). ExcludeHitTriangle: at the hit point itself, ignoring the
// triangle they leave, which is what the 2017-2019 CENG477 reference renderer did.
enum class SecondaryRayStart { Offset, ExcludeHitTriangle };

// How a pixel's radiance becomes an 8-bit channel: rounded to nearest (rayview's images), or truncated, as the
// 2017-2020 course reference renderers did (their images are the truncated ones).
enum class Quantization { Round, Truncate };

inline constexpr int kMaxPixelSamples = 256;

struct RenderSettings {
  TriangularLightModel triangularLightModel = TriangularLightModel::Area;
  int lightSamples = 1;       // samples per triangular light (area model); 1 = the centroid
  AccelKind accel = AccelKind::Embree;  // the packet BVH in its place when built without Embree (availableAccel)
  SecondaryRayStart secondaryRayStart = SecondaryRayStart::Offset;
  int pixelSamples = 1;       // anti-aliasing: stratified camera rays per pixel; 1 = the pixel's centre
  Quantization quantization = Quantization::Round;  // radiance to 8 bits (quantizeChannel)

  bool operator==(const RenderSettings&) const = default;
};

std::string_view toString(AccelKind kind);
bool parseAccelKind(std::string_view text, AccelKind& out);
std::string_view toString(SecondaryRayStart start);
bool parseSecondaryRayStart(std::string_view text, SecondaryRayStart& out);

// The accelerator actually used for `requested` in this build.
AccelKind availableAccel(AccelKind requested);

}  // namespace rayview
