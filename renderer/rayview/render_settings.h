#pragma once
// Every knob of a render, with its default: the command line, the viewer and restarts all use this one struct.

#include <string>
#include <string_view>

namespace rayview {

enum class TriangularLightModel { Area, Directional };
enum class AccelKind { Embree, Reference };

// Where shadow and mirror rays start. Offset: off the surface (by <shadowrayepsilon> when the scene sets
// it, else by the robust relative offset). ExcludeHitTriangle: at the hit point itself, ignoring the
// triangle they leave, which is what the 2017-2019 CENG477 reference renderer did.
enum class SecondaryRayStart { Offset, ExcludeHitTriangle };

struct RenderSettings {
  int maxDepthOverride = -1;  // -1: the scene's <maxraytracedepth>
  TriangularLightModel triangularLightModel = TriangularLightModel::Area;
  int lightSamples = 1;       // samples per triangular light (area model); 1 = the centroid
  AccelKind accel = AccelKind::Embree;  // falls back to Reference when built without Embree
  SecondaryRayStart secondaryRayStart = SecondaryRayStart::Offset;

  bool operator==(const RenderSettings&) const = default;
};

inline constexpr int kMaxLightSamples = 4096;

std::string_view toString(TriangularLightModel model);
std::string_view toString(AccelKind kind);
bool parseTriangularLightModel(std::string_view text, TriangularLightModel& out);
bool parseAccelKind(std::string_view text, AccelKind& out);
std::string_view toString(SecondaryRayStart start);
bool parseSecondaryRayStart(std::string_view text, SecondaryRayStart& out);

// The accelerator actually used for `requested` in this build.
AccelKind availableAccel(AccelKind requested);

}  // namespace rayview
