#pragma once
// What the viewer makes of a finished speed-vs-accuracy measurement (docs/viewer.md, "Speed vs accuracy"): one
// line of advice, and applying a row's setting to what the user has, as the Render panel's widget would. No GL.

#include <string>

#include "rayview/knobs.h"
#include "rayview/tradeoff.h"

namespace rayview {

class SceneSession;

// The advice suggests the fastest render setting that keeps all but kAdvicePctOff % of the pixels within 1 of
// the best image, when it is faster than the user's settings (the baseline) or they are further off. Preview
// levels are not candidates: the viewer picks those itself, a user cannot.
inline constexpr double kAdvicePctOff = 1.0;
// The suggested row, or nullptr (nothing close enough, or the user's settings are already enough).
const TradeoffPoint* tradeoffSuggestion(const TradeoffReport& report);
// One line: the suggestion, with the best image's time and that of the user's settings for comparison, or why
// there is none. "" without the best image and the baseline among the points.
std::string tradeoffAdvice(const TradeoffReport& report);

// The row that sets `knob` to `value`, or nullptr.
const TradeoffPoint* findTradeoffRow(const TradeoffReport& report, const Knob& knob, int value);

// Sets the knob the row varies to the row's value in the session's edits and settings, through the knob
// table's setter as the Render panel does: the next commit() restarts the render (or rebuilds the BVH, for the
// traversal) and records one undo step. False, and nothing changed, for a row that is not a render setting
// (the best image, a preview level).
bool applyKnobSetting(SceneSession& session, const KnobSetting& setting);

}  // namespace rayview
