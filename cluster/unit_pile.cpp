#include "unit_pile.h"

namespace rayview::cluster {

UnitPile::UnitPile(std::size_t units) : holder_(units, kNobody), done_(units, false) {
  for (std::size_t k = 0; k < units; ++k) pile_.push_back(k);
}

std::optional<std::size_t> UnitPile::takeLocked(int rank) {
  while (!pile_.empty()) {
    const std::size_t unit = pile_.front();
    pile_.pop_front();
    if (done_[unit]) continue;  // finished late by the rank it was reclaimed from
    holder_[unit] = rank;
    return unit;
  }
  return std::nullopt;
}

std::optional<std::size_t> UnitPile::take(int rank) {
  std::lock_guard lock(mutex_);
  return takeLocked(rank);
}

std::optional<std::size_t> UnitPile::next() const {
  std::lock_guard lock(mutex_);
  for (std::size_t unit : pile_)
    if (!done_[unit]) return unit;
  return std::nullopt;
}

std::optional<std::size_t> UnitPile::takeOrWait(int rank) {
  std::unique_lock lock(mutex_);
  for (;;) {
    if (const auto unit = takeLocked(rank)) return unit;
    if (stopped_ || finished_ == holder_.size()) return std::nullopt;
    changed_.wait(lock);
  }
}

bool UnitPile::finish(std::size_t unit) {
  std::lock_guard lock(mutex_);
  if (unit >= done_.size() || done_[unit]) return false;
  done_[unit] = true;
  holder_[unit] = kNobody;
  if (++finished_ == holder_.size()) changed_.notify_all();
  return true;
}

std::vector<std::size_t> UnitPile::reclaim(int rank) {
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

std::vector<std::size_t> UnitPile::heldBy(int rank) const {
  std::lock_guard lock(mutex_);
  std::vector<std::size_t> held;
  for (std::size_t k = 0; k < holder_.size(); ++k)
    if (holder_[k] == rank && !done_[k]) held.push_back(k);
  return held;
}

void UnitPile::stop() {
  {
    std::lock_guard lock(mutex_);
    stopped_ = true;
  }
  changed_.notify_all();
}

std::size_t UnitPile::finished() const {
  std::lock_guard lock(mutex_);
  return finished_;
}

}  // namespace rayview::cluster
