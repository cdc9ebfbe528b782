#include "rayview/knobs.h"

#include <charconv>

#include "accel_backends.h"

namespace rayview {
namespace {

constexpr KnobChoice kTriangularLightModels[] = {{"area", "area"}, {"directional", "directional"}};
constexpr KnobChoice kAccelKinds[] = {{"embree", "Embree"}, {"reference", "reference BVH"}, {"packet", "packet BVH"}};
static_assert(kPacketBvhTriangles == 5000, "the accel row's help below names prepareGeometry's limit");
constexpr KnobChoice kQuantizations[] = {{"round", "round to nearest"}, {"truncate", "truncate"}};
constexpr KnobChoice kRayStarts[] = {{"offset", "offset off the surface"},
                                     {"exclude-hit", "at the hit, skip its triangle"}};

bool always(const SceneParameters&, const RenderSettings&) { return true; }

// The trade-off measures the fast traversal this build has (Embree, or the packet BVH in its place: the row's setter
// makes it so) against the reference BVH.
constexpr int kAccelSwept[] = {static_cast<int>(AccelKind::Embree), static_cast<int>(AccelKind::Reference)};

const Knob kKnobs[] = {
    {.name = "depth",
     .label = "Max ray depth",
     .help = "maximum mirror recursion depth",
     .defaultNote = "the scene's <maxraytracedepth>",
     .home = KnobHome::Parameters,
     .min = 0,
     .max = kMaxRayDepth,
     .tradeoff = {.kind = TradeoffSweep::UpToScene,
                  .changesImage = [](const SceneParameters& p) { return p.hasMirrors(); }},
     .get = [](const SceneParameters& p, const RenderSettings&) { return p.maxRayDepth; },
     .set = [](SceneParameters& p, RenderSettings&, int v) { p.maxRayDepth = v; },
     .matters = always},
    {.name = "tri-light",
     .label = "Tri-light model",
     .help = "triangular-light model",
     .home = KnobHome::Settings,
     .choices = kTriangularLightModels,
     .get = [](const SceneParameters&, const RenderSettings& s) { return static_cast<int>(s.triangularLightModel); },
     .set = [](SceneParameters&, RenderSettings& s, int v) { s.triangularLightModel = static_cast<TriangularLightModel>(v); },
     .matters = [](const SceneParameters& p, const RenderSettings&) { return !p.lights.of<TriangularLight>().empty(); }},
    {.name = "light-samples",
     .label = "Light samples",
     .help = "samples per triangular light, area model",
     .defaultNote = "the centroid",
     .home = KnobHome::Settings,
     .min = 1,
     .max = kMaxLightSamples,
     .tradeoff = {.kind = TradeoffSweep::Doublings, .max = 256, .best = 256},
     .get = [](const SceneParameters&, const RenderSettings& s) { return s.lightSamples; },
     .set = [](SceneParameters&, RenderSettings& s, int v) { s.lightSamples = v; },
     .matters = [](const SceneParameters& p, const RenderSettings& s) {
       return !p.lights.of<TriangularLight>().empty() && s.triangularLightModel == TriangularLightModel::Area;
     }},
    {.name = "accel",
     .label = "Traversal",
     .help = "ray traversal: Embree (fast; rayview's packet BVH for scenes of up to 5000 triangles, where Embree's "
             "start-up costs more than it saves), the double-precision reference BVH, or rayview's packet BVH at any "
             "size",
     .home = KnobHome::Settings,
     .choices = kAccelKinds,
     .tradeoff = {.kind = TradeoffSweep::Values, .values = kAccelSwept, .best = static_cast<int>(AccelKind::Reference)},
     .get = [](const SceneParameters&, const RenderSettings& s) { return static_cast<int>(s.accel); },
     .set = [](SceneParameters&, RenderSettings& s, int v) { s.accel = availableAccel(static_cast<AccelKind>(v)); },
     .matters = always},
    {.name = "ray-start",
     .label = "Ray start",
     .help = "where shadow/mirror rays start: offset off the surface, or at the hit point ignoring its "
             "triangle (the 2017-19 course renderer)",
     .home = KnobHome::Settings,
     .choices = kRayStarts,
     .get = [](const SceneParameters&, const RenderSettings& s) { return static_cast<int>(s.secondaryRayStart); },
     .set = [](SceneParameters&, RenderSettings& s, int v) { s.secondaryRayStart = static_cast<SecondaryRayStart>(v); },
     .matters = always},
    {.name = "samples",
     .label = "Samples per pixel",
     .help = "anti-aliasing: stratified camera rays per pixel, the same for any thread count",
     .defaultNote = "the pixel's centre, as the course's images",
     .home = KnobHome::Settings,
     .min = 1,
     .max = kMaxPixelSamples,
     .tradeoff = {.kind = TradeoffSweep::Doublings, .max = 16},
     .get = [](const SceneParameters&, const RenderSettings& s) { return s.pixelSamples; },
     .set = [](SceneParameters&, RenderSettings& s, int v) { s.pixelSamples = v; },
     .matters = always},
    {.name = "quantize",
     .label = "Quantisation",
     .help = "radiance to 8 bits: round to nearest, or truncate, as the 2017-2020 course reference "
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

std::string Knob::defaultText() const {
  if (home == KnobHome::Parameters) return std::string(defaultNote);
  const std::string value = format(get(SceneParameters{}, RenderSettings{}));
  return defaultNote.empty() ? value : value + " = " + std::string(defaultNote);
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

std::string describeKnobValues(const SceneParameters& parameters, const RenderSettings& settings) {
  std::string text;
  for (const Knob& k : kKnobs) {
    if (!text.empty()) text += ", ";
    text += k.name;
    text += ' ';
    text += k.format(k.get(parameters, settings));
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
