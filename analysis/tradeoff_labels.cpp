// The words users see for the trade-off measurement (tradeoff.h): the Render panel's labels, from the knob
// table (renderer/knobs.cpp), its one owner; and the knob-table values of its rows.
#include "rayview/tradeoff.h"

namespace rayview {

std::string_view knobLabel(TradeoffKnob knob) {
  if (const Knob* row = tableKnob(knob)) return row->label;
  // The stats over the image call the viewer's passes so.
  return knob == TradeoffKnob::Preview ? std::string_view("Preview level") : kBestImageLabel;
}

std::optional<int> knobValue(const KnobSetting& setting) {
  const Knob* row = tableKnob(setting.knob);
  if (!row) return std::nullopt;
  SceneParameters parameters;
  parameters.maxRayDepth = setting.depth;
  return row->get(parameters, setting.settings);
}

std::string settingLabel(const KnobSetting& setting) {
  if (setting.knob == TradeoffKnob::BestImage) return {};
  const std::optional<int> value = knobValue(setting);
  return value ? tableKnob(setting.knob)->formatLabel(*value) : setting.label;
}

std::string describeRow(const KnobSetting& setting) {
  const std::string value = settingLabel(setting);
  return std::string(knobLabel(setting.knob)) + (value.empty() ? "" : " " + value);
}

}  // namespace rayview
