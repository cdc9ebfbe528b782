#include "render_progress.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace rayview {
namespace {

// A rate measured over less than this says nothing yet: no time left is shown.
constexpr double kMinSecondsForRate = 0.25;

}  // namespace

RenderProgress RenderProgressEstimate::update(std::uint64_t generation, int samplesDone, int samplesTotal,
                                              double passFraction, Clock::time_point now) {
  RenderProgress p;
  p.samplesTotal = std::max(samplesTotal, 1);
  p.samplesDone = std::clamp(samplesDone, 0, p.samplesTotal);
  p.passFraction = std::clamp(passFraction, 0.0, 1.0);
  // The pass in flight may already be the next sample's while the frame on screen still says the one before:
  // never shown as going back.
  const double doneSamples =
      std::min(static_cast<double>(p.samplesTotal), static_cast<double>(p.samplesDone) + p.passFraction);
  if (generation != generation_) {
    generation_ = generation;
    since_ = now;
    startSamples_ = doneSamples;
    best_ = doneSamples;
  }
  best_ = std::max(best_, doneSamples);
  p.renderFraction = best_ / p.samplesTotal;
  const double seconds = std::chrono::duration<double>(now - since_).count();
  const double gained = best_ - startSamples_;
  if (seconds >= kMinSecondsForRate && gained > 0.0) p.secondsLeft = (p.samplesTotal - best_) * seconds / gained;
  return p;
}

std::string describeProgress(const RenderProgress& p) {
  char text[128];
  if (p.samplesTotal <= 1) {
    std::snprintf(text, sizeof text, "full resolution: %.0f%%", 100.0 * p.passFraction);
    return text;
  }
  std::snprintf(text, sizeof text, "samples %d/%d, %.0f%% of the render", p.samplesDone, p.samplesTotal,
                100.0 * p.renderFraction);
  std::string out = text;
  if (p.secondsLeft) {
    const double left = std::ceil(*p.secondsLeft);
    if (left >= 120.0) std::snprintf(text, sizeof text, ", %.0f min left", std::ceil(left / 60.0));
    else std::snprintf(text, sizeof text, ", %.0f s left", std::max(left, 1.0));
    out += text;
  }
  return out;
}

}  // namespace rayview
