#include "frame_units.h"

#include <algorithm>

#include "tile_plan.h"
#include "tile_render.h"

namespace rayview::cluster {

std::vector<WorkUnit> frameUnits(int frames, int width, int height, int ranks) {
  std::vector<WorkUnit> units;
  const std::vector<Tile> tiles = clusterTiles(width, height, ranks);
  for (int f = 0; f < frames; ++f) {
    if (frames - f >= ranks) {
      units.push_back({f, Tile{0, 0, width, height}, true});
      continue;
    }
    for (const Tile& tile : tiles) units.push_back({f, tile, false});
  }
  return units;
}

std::vector<WorkUnit> tileUnits(const std::vector<Tile>& tiles) {
  std::vector<WorkUnit> units;
  for (const Tile& tile : tiles) units.push_back({0, tile, false});
  return units;
}

FrameAssembly::FrameAssembly(const std::vector<WorkUnit>& units, Done done) : units_(units), done_(std::move(done)) {
  for (const WorkUnit& unit : units) {
    const auto f = static_cast<std::size_t>(unit.frame);
    if (f >= missing_.size()) missing_.resize(f + 1, 0), extent_.resize(f + 1), images_.resize(f + 1);
    ++missing_[f];
    extent_[f].x1 = std::max(extent_[f].x1, unit.tile.x1);
    extent_[f].y1 = std::max(extent_[f].y1, unit.tile.y1);
  }
}

void FrameAssembly::place(std::size_t unit, const std::uint8_t* rgb) {
  const WorkUnit& u = units_.at(unit);
  const auto f = static_cast<std::size_t>(u.frame);
  Image finished;
  {
    std::lock_guard lock(mutex_);
    if (images_[f].rgb.empty()) images_[f] = Image(extent_[f].x1, extent_[f].y1);
    placeTile(u.tile, rgb, images_[f]);
    if (--missing_[f] > 0) return;
    finished = std::move(images_[f]);
    images_[f] = Image();
  }
  std::lock_guard lock(doneMutex_);
  if (!done_(u.frame, std::move(finished))) {
    std::lock_guard state(mutex_);
    failed_ = true;
  }
}

bool FrameAssembly::failed() const {
  std::lock_guard lock(mutex_);
  return failed_;
}

}  // namespace rayview::cluster
