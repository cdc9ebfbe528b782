// The viewer's side of the progressive render: restarts, taking passes, their stats and texture.
#include "render_controller.h"

#include <cstdio>
#include <utility>

#include <GLFW/glfw3.h>

#include "rayview/process_memory.h"

namespace rayview {

RenderController::RenderController(int threads, std::shared_ptr<PassFarm> farm)
    : farm_(farm), renderer_(threads, std::move(farm)) {
  stats_.threads = renderer_.threads();
  // Wake the UI loop when a pass is published, so it can sleep while passes render.
  renderer_.setFrameListener([] { glfwPostEmptyEvent(); });
}

RenderController::~RenderController() {
  renderer_.restart(nullptr);  // stop the pass in flight now rather than let the renderer finish it on exit
}

void RenderController::restart(std::shared_ptr<const PixelSource> source) {
  generation_ = renderer_.restart(std::move(source));
}

void RenderController::setInteractive(bool dragging) {
  if (dragging == interactive_) return;
  interactive_ = dragging;
  renderer_.setInteractive(dragging);
}

bool RenderController::takeNewFrame() {
  if (!renderer_.takeFrameIfNewer(seenVersion_, incoming_)) return false;
  seenVersion_ = incoming_.version;
  // A pass that was published just before the latest restart belongs to the old edits: never show it.
  if (incoming_.generation < generation_) return false;
  std::swap(frame_, incoming_);
  haveFrame_ = true;
  stats_.generation = frame_.generation;
  stats_.editToFirstPassMs = frame_.firstPassMsSinceRestart;
  stats_.editToFinalPassMs = frame_.final ? frame_.msSinceRestart : -1.0;
  stats_.stride = frame_.stride;
  stats_.samples = frame_.samples;
  stats_.final = frame_.final;
  stats_.passMs = frame_.passMs;
  stats_.megaRaysPerSecond = frame_.megaRaysPerSecond;
  // Read with each pass shown: at most once a frame drawn, never while idle (rayview/process_memory.h: ~20 us).
  const ProcessMemory memory = processMemory();
  stats_.residentBytes = memory.resident;
  stats_.peakResidentBytes = memory.peak;
  if (farm_) {
    stats_.tracedBy = farm_->describe();
    // A rank lost is said once on stdout as well as in the stats, for the user and for tools driving the window.
    std::vector<std::string> lost = farm_->lostRanks();
    for (std::size_t k = stats_.lostRanks.size(); k < lost.size(); ++k) std::printf("lost %s\n", lost[k].c_str());
    if (lost.size() != stats_.lostRanks.size()) std::fflush(stdout);
    stats_.lostRanks = std::move(lost);
  }
  stats_.width = frame_.width;
  stats_.height = frame_.height;
  return true;
}

void RenderController::announceFinal() {
  if (!haveFrame_ || announcedFinal_ == frame_.generation) return;
  announcedFinal_ = frame_.generation;
  // Tests and tools driving the window wait for this line.
  std::printf("final pass generation %llu\n", static_cast<unsigned long long>(frame_.generation));
  std::fflush(stdout);
}

std::optional<RenderProgress> RenderController::fullPassProgress(std::chrono::steady_clock::time_point now) {
  const PassProgress pass = renderer_.passProgress();
  const bool onScreen = haveFrame_ && frame_.generation == generation_ && frame_.final;
  if (pass.stride != 1 || pass.generation != generation_ || onScreen || renderer_.idle()) return std::nullopt;
  // Each anti-aliasing sample is a full pass of its own; the bar is of them all. A coarse pass on screen says
  // how many samples the render takes but that none is complete at full resolution yet.
  const bool ofThis = haveFrame_ && frame_.generation == generation_;
  const int samplesDone = ofThis && frame_.stride == 1 ? frame_.samples.done : 0;
  const RenderProgress progress =
      progress_.update(pass.generation, samplesDone, ofThis ? frame_.samples.total : 1, pass.fraction, now);
  if (now - progress_.since() < kProgressAfter) return std::nullopt;
  return progress;
}

const ImageTexture& RenderController::texture(const DisplayMapping& mapping) {
  if (haveFrame_) texture_.update(shownRender_.of(frame_.image, frame_.version, mapping), shownRender_.serial());
  return texture_;
}

}  // namespace rayview
