#pragma once
// How far the whole render is once it traces full-resolution passes, and the time it still needs: with N samples
// per pixel, N full passes, so one pass's bar says little (a 16-sample render would show sixteen bars in turn).
// No GL, no threads: fed by RenderController on the UI thread.

#include <chrono>
#include <cstdint>
#include <optional>
#include <string>

namespace rayview {

struct RenderProgress {
  int samplesDone = 0;   // full-resolution samples every pixel has
  int samplesTotal = 1;  // the render's samples per pixel
  double passFraction = 0.0;    // of the pass in flight
  double renderFraction = 0.0;  // of the whole render's full-resolution work
  std::optional<double> secondsLeft;  // once a rate has been measured
};

// "full resolution: 43%" for one sample per pixel; with several, "samples 3/16, 21% of the render, 12 s left".
std::string describeProgress(const RenderProgress& progress);

class RenderProgressEstimate {
 public:
  using Clock = std::chrono::steady_clock;
  // The full-resolution pass of `generation` in flight: `samplesDone` of `samplesTotal` complete, `passFraction`
  // of the next. Returns the render's progress; the fraction never goes back within one generation.
  RenderProgress update(std::uint64_t generation, int samplesDone, int samplesTotal, double passFraction,
                        Clock::time_point now);
  // When the render's full passes were first seen (for the bar's delay): the start of this generation's.
  Clock::time_point since() const { return since_; }

 private:
  std::uint64_t generation_ = 0;
  Clock::time_point since_{};
  double startSamples_ = 0.0;  // samples' worth done when first seen
  double best_ = 0.0;          // the furthest seen, in samples
};

}  // namespace rayview
