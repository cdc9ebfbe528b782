#pragma once
// The progressive render as the viewer sees it: restarts, the newest pass of the latest restart, the stats of
// the pass on screen and its texture as displayed. The ProgressiveRenderer renders on its own threads; this
// only hands it sources and takes its passes on the UI thread.

#include <chrono>
#include <cstdint>
#include <memory>
#include <optional>

#include "display_mapping.h"
#include "image_texture.h"
#include "panels.h"
#include "rayview/progressive_renderer.h"
#include "render_progress.h"

namespace rayview {

// A full-resolution pass gets a progress bar once it has run this long.
inline constexpr std::chrono::milliseconds kProgressAfter{500};

class RenderController {
 public:
  // threads <= 0: one per hardware thread; a farm traces the passes elsewhere (rayview/pass_farm.h).
  explicit RenderController(int threads, std::shared_ptr<PassFarm> farm = nullptr);
  ~RenderController();
  RenderController(const RenderController&) = delete;
  RenderController& operator=(const RenderController&) = delete;

  // A new source (null: stop rendering; the pass on screen stays). Returns at once.
  void restart(std::shared_ptr<const PixelSource> source);
  bool idle() const { return renderer_.idle(); }
  // The user drags: hold the coarse level, one pass per move.
  void setInteractive(bool dragging);

  // Takes the newest pass of the latest restart; false when there is none newer.
  bool takeNewFrame();
  bool haveFrame() const { return haveFrame_; }
  const ProgressiveFrame& frame() const { return frame_; }
  std::uint64_t generation() const { return generation_; }
  // The pass on screen is the final pass of the latest restart, and has been drawn.
  bool finalPassShown() const {
    return haveFrame_ && frame_.final && frame_.generation == generation_ && shownVersion_ == frame_.version;
  }
  // The pass on screen has the size of `camera`'s image (not a pass of another view or size still showing).
  bool frameIsOfSize(int width, int height) const { return haveFrame_ && frame_.width == width && frame_.height == height; }
  // After a swap: the pass is on screen.
  void markDrawn() {
    if (haveFrame_) shownVersion_ = frame_.version;
  }
  // Prints the final pass's line, once per restart (call when the final pass of the current edits is on screen).
  void announceFinal();

  // The pass on screen as displayed (exposure and gamma), uploaded if it or the mapping changed.
  const ImageTexture& texture(const DisplayMapping& mapping);
  bool isRenderTexture(const ImageTexture& texture) const { return &texture == &texture_; }

  // How far the full-resolution passes of the latest restart are (with several samples per pixel, the whole render:
  // samples done of total, time left), once they have run for kProgressAfter and while the final pass is not on
  // screen; nullopt otherwise (short renders show no bar).
  std::optional<RenderProgress> fullPassProgress(std::chrono::steady_clock::time_point now);

  ViewerStats& stats() { return stats_; }
  const ViewerStats& stats() const { return stats_; }

 private:
  std::shared_ptr<PassFarm> farm_;  // null: this process's threads trace
  ProgressiveRenderer renderer_;
  std::uint64_t generation_ = 0;  // of the latest restart
  ProgressiveFrame frame_;        // the newest pass of generation_ (or the last one before it): what is shown
  ProgressiveFrame incoming_;     // scratch for takeFrameIfNewer
  std::uint64_t seenVersion_ = 0;
  bool haveFrame_ = false;
  std::uint64_t shownVersion_ = 0;
  std::uint64_t announcedFinal_ = 0;
  bool interactive_ = false;
  ViewerStats stats_;
  RenderProgressEstimate progress_;
  ImageTexture texture_;  // the render as displayed
  MappedImage shownRender_;
};

}  // namespace rayview
