#include "rayview/knobs.h"

#include <charconv>

#include "accel_backends.h"
#include "rayview/lean_memory.h"

namespace rayview {
namespace {

constexpr KnobChoice kTriangularLightModels[] = {{"area", "area"}, {"directional", "directional"}};
constexpr KnobChoice kAccelKinds[] = {{"embree", "Embree"}, {"reference", "reference BVH"}, {"packet", "packet BVH"}};
static_assert(kPacketBvhTriangles == 5000, "the accel row's help below names prepareGeometry's limit");
static_assert(kLeanFromTriangles == 100'000 && kLeanUntilTriangles == 1'000'000, "and its lean scenes' sizes");
constexpr KnobChoice kQuantizations[] = {{"round", "round to nearest"}, {"truncate", "truncate"}};
constexpr KnobChoice kRayStarts[] = {{"offset", "offset off the surface"},
                                     {"exclude-hit", "at the hit, skip its triangle"}};

bool always(const SceneParameters&, const RenderSettings&) { return true; }

const Knob kKnobs[] = {
    {.name = "depth",
     .label = "Max ray depth",
     .help = "maximum mirror recursion depth (default: the scene's <maxraytracedepth>)",
     .home = KnobHome::Parameters,
     .min = 0,
     .max = kMaxRayDepth,
     .measuredByTradeoff = true,
     .get = [](const SceneParameters& p, const RenderSettings&) { return p.maxRayDepth; },
     .set = [](SceneParameters& p, RenderSettings&, int v) { p.maxRayDepth = v; },
     .matters = always},
    {.name = "tri-light",
     .label = "Tri-light model",
     .help = "triangular-light model (default: area)",
     .home = KnobHome::Settings,
     .choices = kTriangularLightModels,
     .get = [](const SceneParameters&, const RenderSettings& s) { return static_cast<int>(s.triangularLightModel); },
     .set = [](SceneParameters&, RenderSettings& s, int v) { s.triangularLightModel = static_cast<TriangularLightModel>(v); },
     .matters = [](const SceneParameters& p, const RenderSettings&) { return !p.lights.of<TriangularLight>().empty(); }},
    {.name = "light-samples",
     .label = "Light samples",
     .help = "samples per triangular light, area model (default: 1 = the centroid)",
     .home = KnobHome::Settings,
     .min = 1,
     .max = kMaxLightSamples,
     .measuredByTradeoff = true,
     .get = [](const SceneParameters&, const RenderSettings& s) { return s.lightSamples; },
     .set = [](SceneParameters&, RenderSettings& s, int v) { s.lightSamples = v; },
     .matters = [](const SceneParameters& p, const RenderSettings& s) {
       return !p.lights.of<TriangularLight>().empty() && s.triangularLightModel == TriangularLightModel::Area;
     }},
    {.name = "accel",
     .label = "Traversal",
     .help = "ray traversal: Embree (fast; rayview's packet BVH for scenes of up to 5000 triangles, and with leaves "
             "of several triangles from 100 000 to 1 000 000 in `rayview render`, to save memory), the "
             "double-precision reference BVH, or rayview's packet BVH at any size",
     .home = KnobHome::Settings,
     .choices = kAccelKinds,
     .measuredByTradeoff = true,
     .get = [](const SceneParameters&, const RenderSettings& s) { return static_cast<int>(s.accel); },
     .set = [](SceneParameters&, RenderSettings& s, int v) { s.accel = availableAccel(static_cast<AccelKind>(v)); },
     .matters = always},
    {.name = "ray-start",
     .label = "Ray start",
     .help = "where shadow/mirror rays start: offset off the surface (default), or at the hit point ignoring its "
             "triangle (the 2017-19 course renderer)",
     .home = KnobHome::Settings,
     .choices = kRayStarts,
     .get = [](const SceneParameters&, const RenderSettings& s) { return static_cast<int>(s.secondaryRayStart); },
     .set = [](SceneParameters&, RenderSettings& s, int v) { s.secondaryRayStart = static_cast<SecondaryRayStart>(v); },
     .matters = always},
    {.name = "samples",
     .label = "Samples per pixel",
     .help = "anti-aliasing: stratified camera rays per pixel, the same for any thread count (default: 1, "
             "the pixel's centre, as the course's images)",
     .home = KnobHome::Settings,
     .min = 1,
     .max = kMaxPixelSamples,
     .measuredByTradeoff = true,
     .get = [](const SceneParameters&, const RenderSettings& s) { return s.pixelSamples; },
     .set = [](SceneParameters&, RenderSettings& s, int v) { s.pixelSamples = v; },
     .matters = always},
    {.name = "quantize",
     .label = "Quantisation",
     .help = "radiance to 8 bits: round to nearest (default), or truncate, as the 2017-2020 course reference "
             "images did",
     .home = KnobHome::Settings,
     .choices = kQuantizations,
     .get = [](const SceneParameters&, const RenderSettings& s) { return static_cast<int>(s.quantization); },
     .set = [](SceneParameters&, RenderSettings& s, int v) { s.quantization = static_cast<Quantization>(v); },
     .matters = always},
};

}  // namespace

std::string Knob::valueName() const {
  if (!isChoice()) return "N";
  std::string text;
  for (const KnobChoice& c : choices) {
    if (!text.empty()) text += '|';
    text += c.name;
  }
  return text;
}

std::string Knob::expectation() const {
  if (!isChoice()) return "an integer from " + std::to_string(min) + " to " + std::to_string(max);
  std::string text;
  for (std::size_t i = 0; i < choices.size(); ++i) {
    if (i > 0) text += i + 1 == choices.size() ? " or " : ", ";
    text += '\'';
    text += choices[i].name;
    text += '\'';
  }
  return text;
}

std::optional<int> Knob::parse(std::string_view text) const {
  if (isChoice()) {
    for (std::size_t i = 0; i < choices.size(); ++i)
      if (text == choices[i].name) return static_cast<int>(i);
    return std::nullopt;
  }
  int value = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error != std::errc() || end != text.data() + text.size() || value < min || value > max) return std::nullopt;
  return value;
}

std::string Knob::format(int value) const {
  if (isChoice()) return value >= 0 && value < static_cast<int>(choices.size()) ? std::string(choices[value].name) : "?";
  return std::to_string(value);
}

std::string Knob::formatLabel(int value) const {
  if (isChoice()) return value >= 0 && value < static_cast<int>(choices.size()) ? std::string(choices[value].label) : "?";
  return std::to_string(value);
}

std::string Knob::csvName() const {
  std::string text(name);
  for (char& c : text)
    if (c == '-') c = '_';
  return text;
}

std::span<const Knob> knobTable() { return kKnobs; }

const Knob* findKnob(std::string_view name) {
  for (const Knob& k : kKnobs)
    if (k.name == name) return &k;
  return nullptr;
}

std::string describeKnobs(const SceneParameters& parameters, const RenderSettings& settings) {
  std::string text;
  for (const Knob& k : kKnobs) {
    if (!k.matters(parameters, settings)) continue;
    if (!text.empty()) text += ", ";
    text += k.label;
    text += ' ';
    text += k.formatLabel(k.get(parameters, settings));
  }
  return text;
}

const Knob& depthKnob() { return *findKnob("depth"); }
const Knob& lightSamplesKnob() { return *findKnob("light-samples"); }
const Knob& accelKnob() { return *findKnob("accel"); }
const Knob& pixelSamplesKnob() { return *findKnob("samples"); }

void applyKnobs(std::span<const KnobAssignment> assignments, KnobTarget target) {
  // A row's setter writes only its home; the other reference is a stand-in that is never written.
  SceneParameters noParameters;
  RenderSettings noSettings;
  SceneParameters& parameters = target.parameters ? *target.parameters : noParameters;
  RenderSettings& settings = target.settings ? *target.settings : noSettings;
  for (const KnobAssignment& a : assignments) {
    const bool present = a.knob->home == KnobHome::Parameters ? target.parameters != nullptr : target.settings != nullptr;
    if (present) a.knob->set(parameters, settings, a.value);
  }
}

}  // namespace rayview
