#include "worker_watch.h"

namespace rayview::cluster {

WorkerWatch::WorkerWatch(int ranks, const std::vector<bool>& lostBefore)
    : ranks_(ranks), loss_(std::make_unique<std::atomic<int>[]>(static_cast<std::size_t>(ranks))),
      owedSince_(static_cast<std::size_t>(ranks)), lastSent_(static_cast<std::size_t>(ranks), Clock::now()) {
  for (std::size_t r = 0; r < static_cast<std::size_t>(ranks); ++r)
    loss_[r].store(r < lostBefore.size() && lostBefore[r] ? kSilent : kNotLost);
}

std::vector<bool> WorkerWatch::lostRanks() const {
  std::vector<bool> lostOnes(static_cast<std::size_t>(ranks_));
  for (int r = 0; r < ranks_; ++r) lostOnes[static_cast<std::size_t>(r)] = lost(r);
  return lostOnes;
}

bool WorkerWatch::lose(int worker, int why) {
  int none = kNotLost;
  if (!loss_[static_cast<std::size_t>(worker)].compare_exchange_strong(none, why)) return false;
  owedSince_[static_cast<std::size_t>(worker)].reset();
  return true;
}

void WorkerWatch::dealt(int worker, Clock::time_point now) {
  auto& since = owedSince_[static_cast<std::size_t>(worker)];
  if (!since) since = now;
}

void WorkerWatch::heard(int worker, bool holding) {
  owedSince_[static_cast<std::size_t>(worker)] = holding ? std::optional(Clock::now()) : std::nullopt;
}

bool WorkerWatch::owedLongerThan(int worker, Clock::time_point now, Clock::duration patience) const {
  const auto& since = owedSince_[static_cast<std::size_t>(worker)];
  return since && now - *since > patience;
}

}  // namespace rayview::cluster
