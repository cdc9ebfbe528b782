#include "tradeoff_advice.h"

#include <cstdio>

#include "scene_session.h"

namespace rayview {
namespace {

struct AdviceParts {
  const TradeoffPoint* best = nullptr;
  const TradeoffPoint* yours = nullptr;    // the baseline: the user's settings
  const TradeoffPoint* fastest = nullptr;  // the fastest render setting within kAdvicePctOff
};

AdviceParts adviceParts(const TradeoffReport& report) {
  AdviceParts parts;
  for (const TradeoffPoint& p : report.points) {
    if (p.setting.knob == TradeoffKnob::BestImage) parts.best = &p;
    if (p.setting.knob == TradeoffKnob::Preview && p.setting.stride == 1) parts.yours = &p;
    if (!tableKnob(p.setting.knob) || p.error.pctOffByMoreThan1 > kAdvicePctOff) continue;
    if (!parts.fastest || p.timeMs < parts.fastest->timeMs) parts.fastest = &p;
  }
  return parts;
}

bool yoursAreEnough(const AdviceParts& parts) {
  return parts.yours->error.pctOffByMoreThan1 <= kAdvicePctOff && parts.fastest->timeMs >= parts.yours->timeMs;
}

}  // namespace

const TradeoffPoint* tradeoffSuggestion(const TradeoffReport& report) {
  const AdviceParts parts = adviceParts(report);
  if (!parts.best || !parts.yours || !parts.fastest || yoursAreEnough(parts)) return nullptr;
  return parts.fastest;
}

std::string tradeoffAdvice(const TradeoffReport& report) {
  const AdviceParts parts = adviceParts(report);
  const TradeoffPoint *best = parts.best, *yours = parts.yours, *fastest = parts.fastest;
  if (!best || !yours) return {};
  char line[320];
  if (!fastest) {
    std::snprintf(line, sizeof line,
                  "No setting but the best image (%.1f ms) has %g%% of pixels or fewer off by more than 1; your "
                  "settings take %.1f ms with %.1f%% off.",
                  best->timeMs, kAdvicePctOff, yours->timeMs, yours->error.pctOffByMoreThan1);
  } else if (yoursAreEnough(parts)) {
    std::snprintf(line, sizeof line,
                  "Your settings are enough: %.1f ms with %.2f%% of pixels off by more than 1 (the best image: "
                  "%.1f ms).",
                  yours->timeMs, yours->error.pctOffByMoreThan1, best->timeMs);
  } else {
    std::snprintf(line, sizeof line,
                  "Fastest with %g%% of pixels or fewer off by more than 1: %s, %.1f ms (the best image: %.1f ms; "
                  "your settings: %.1f ms with %.1f%% off).",
                  kAdvicePctOff, describeRow(fastest->setting).c_str(), fastest->timeMs, best->timeMs, yours->timeMs,
                  yours->error.pctOffByMoreThan1);
  }
  return line;
}

const TradeoffPoint* findTradeoffRow(const TradeoffReport& report, const Knob& knob, int value) {
  for (const TradeoffPoint& p : report.points)
    if (tableKnob(p.setting.knob) == &knob && knobValue(p.setting) == value) return &p;
  return nullptr;
}

bool applyKnobSetting(SceneSession& session, const KnobSetting& setting) {
  const Knob* knob = tableKnob(setting.knob);
  const std::optional<int> value = knobValue(setting);
  if (!knob || !value) return false;
  knob->set(session.edits(), session.settings(), *value);
  return true;
}

}  // namespace rayview
