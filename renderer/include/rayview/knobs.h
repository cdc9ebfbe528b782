#pragma once
// The render knobs, one table: each row is a setting a user can turn to trade speed for accuracy or to pick a
// rendering rule, with everything the rest of the program needs to know of it. The command line (options and
// --help), the automation `set` commands, the viewer's Render panel and the trade-off bench all read this
// table; adding a knob is one row here plus the code that uses the value.
//
// Each knob has one home: a field of SceneParameters (what the scene file can say, e.g. the depth) or of
// RenderSettings (how to render it). Values are integers: the number itself, or the index of a choice.

#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "rayview/render_settings.h"
#include "rayview/scene.h"

namespace rayview {

enum class KnobHome { Parameters, Settings };

struct KnobChoice {
  std::string_view name;   // on the command line and in scripts: "area"
  std::string_view label;  // in the panel: "area"
};

// Where a knob's value is read and written. A home left null is not there yet (the command line knows the
// settings before the scene is loaded, and the parameters only after).
struct KnobTarget {
  SceneParameters* parameters = nullptr;
  RenderSettings* settings = nullptr;
};

// How the trade-off measurement (analysis/tradeoff.h) varies a knob, each value from the baseline alone.
enum class TradeoffSweep {
  None,       // not measured
  UpToScene,  // 0 .. the scene's value (every value up to 10, then powers of two and the value); only the ends
              // where `changesImage` says the scene would not show a difference
  Doublings,  // 1, 2, 4 .. max, and the baseline's value; only where the knob `matters`
  Values,     // the listed values
};

struct KnobSweep {
  TradeoffSweep kind = TradeoffSweep::None;
  int max = 0;                   // Doublings: the last value (TradeoffOptions can lower it)
  std::span<const int> values = {};  // Values
  // The best image's value: -1 keeps the baseline's; for Doublings at least this many (TradeoffOptions can
  // change it).
  int best = -1;
  bool (*changesImage)(const SceneParameters&) = nullptr;  // UpToScene; null: always
};

struct Knob {
  std::string_view name;       // --NAME, `set NAME`, the trade-off CSV (with '_' for '-')
  std::string_view label;      // the panel's label
  std::string_view help;       // --help and the panel's tooltip
  // What the default means, after its value in --help ("the centroid"); for a Parameters knob, where the
  // default comes from ("the scene's <maxraytracedepth>").
  std::string_view defaultNote = {};
  KnobHome home = KnobHome::Settings;
  int min = 0, max = 0;        // integer knobs; choice knobs take 0 .. choices.size() - 1
  std::span<const KnobChoice> choices = {};  // empty for an integer knob
  // How the trade-off bench varies it (TradeoffSweep::None: it does not; then `bench` takes an option for it).
  KnobSweep tradeoff = {};
  int (*get)(const SceneParameters&, const RenderSettings&) = nullptr;
  void (*set)(SceneParameters&, RenderSettings&, int) = nullptr;
  // Whether the knob changes anything for this scene and these settings (the panel greys it out otherwise).
  bool (*matters)(const SceneParameters&, const RenderSettings&) = nullptr;

  bool isChoice() const { return !choices.empty(); }
  bool measuredByTradeoff() const { return tradeoff.kind != TradeoffSweep::None; }
  // "N", or the choices: "area|directional".
  std::string valueName() const;
  // "an integer from 0 to 1000000", or "'area' or 'directional'".
  std::string expectation() const;
  // The value `text` names (a number in range, or a choice's name), or nothing.
  std::optional<int> parse(std::string_view text) const;
  // The text of `value`: the number, or the choice's name.
  std::string format(int value) const;
  // The text of `value` in the panel: the number, or the choice's label ("reference BVH").
  std::string formatLabel(int value) const;
  // "1 = the centroid", "area", "the scene's <maxraytracedepth>": the default, from RenderSettings{} and the
  // row's note, for --help.
  std::string defaultText() const;
  // The trade-off CSV's name: `name` with '_' for '-'.
  std::string csvName() const;
};

// Every knob, in the order --help and the panel show them.
std::span<const Knob> knobTable();
// The row called `name`, or nullptr.
const Knob* findKnob(std::string_view name);

// "Max ray depth 3, Light samples 4, Traversal Embree, ...": every knob that matters for these parameters and
// settings, by its panel label and value, in the table's order.
std::string describeKnobs(const SceneParameters& parameters, const RenderSettings& settings);

// "depth 3, tri-light area, light-samples 1, ...": every knob's option name and value, in the table's order, as
// `rayview render`'s summary prints them.
std::string describeKnobValues(const SceneParameters& parameters, const RenderSettings& settings);

// The depth knob's row, and the others the trade-off bench refers to.
const Knob& depthKnob();
const Knob& lightSamplesKnob();
const Knob& accelKnob();
const Knob& pixelSamplesKnob();

// A value given for a knob (by an option or a script) before it is written into its home.
struct KnobAssignment {
  const Knob* knob = nullptr;
  int value = 0;
};

// Writes each assignment whose home `target` has; the others are left for a later call.
void applyKnobs(std::span<const KnobAssignment> assignments, KnobTarget target);

}  // namespace rayview
