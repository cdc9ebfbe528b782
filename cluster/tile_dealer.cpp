#include "tile_dealer.h"

namespace rayview::cluster {

TileDealer::TileDealer(std::size_t tiles) : holder_(tiles, kNobody), done_(tiles, false) {
  for (std::size_t k = 0; k < tiles; ++k) pile_.push_back(k);
}

std::optional<std::size_t> TileDealer::take(int rank) {
  std::lock_guard lock(mutex_);
  while (!pile_.empty()) {
    const std::size_t tile = pile_.front();
    pile_.pop_front();
    if (done_[tile]) continue;  // finished late by the rank it was reclaimed from
    holder_[tile] = rank;
    return tile;
  }
  return std::nullopt;
}

std::optional<std::size_t> TileDealer::next() const {
  std::lock_guard lock(mutex_);
  for (std::size_t tile : pile_)
    if (!done_[tile]) return tile;
  return std::nullopt;
}

std::optional<std::size_t> TileDealer::takeOrWait(int rank) {
  std::unique_lock lock(mutex_);
  for (;;) {
    while (!pile_.empty()) {
      const std::size_t tile = pile_.front();
      pile_.pop_front();
      if (done_[tile]) continue;
      holder_[tile] = rank;
      return tile;
    }
    if (stopped_ || finished_ == holder_.size()) return std::nullopt;
    changed_.wait(lock);
  }
}

bool TileDealer::finish(std::size_t tile, int rank) {
  std::lock_guard lock(mutex_);
  (void)rank;
  if (tile >= done_.size() || done_[tile]) return false;
  done_[tile] = true;
  holder_[tile] = kNobody;
  if (++finished_ == holder_.size()) changed_.notify_all();
  return true;
}

std::vector<std::size_t> TileDealer::reclaim(int rank) {
  std::vector<std::size_t> lost;
  {
    std::lock_guard lock(mutex_);
    for (std::size_t k = 0; k < holder_.size(); ++k)
      if (holder_[k] == rank && !done_[k]) {
        holder_[k] = kNobody;
        lost.push_back(k);
      }
    for (auto it = lost.rbegin(); it != lost.rend(); ++it) pile_.push_front(*it);
  }
  changed_.notify_all();
  return lost;
}

std::vector<std::size_t> TileDealer::heldBy(int rank) const {
  std::lock_guard lock(mutex_);
  std::vector<std::size_t> held;
  for (std::size_t k = 0; k < holder_.size(); ++k)
    if (holder_[k] == rank && !done_[k]) held.push_back(k);
  return held;
}

void TileDealer::stop() {
  {
    std::lock_guard lock(mutex_);
    stopped_ = true;
  }
  changed_.notify_all();
}

std::size_t TileDealer::finished() const {
  std::lock_guard lock(mutex_);
  return finished_;
}

}  // namespace rayview::cluster
