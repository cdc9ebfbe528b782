#include "work_dealer.h"

#include <algorithm>
#include <thread>

namespace rayview::cluster {

WorkDealer::WorkDealer(std::size_t units, WorkerWatch& watch, DealRules rules)
    : pile_(units), watch_(watch), rules_(rules), held_(static_cast<std::size_t>(watch.ranks()), 0) {}

bool WorkDealer::run(Dealing& driver) {
  // Each probe runs MPI's progress engine (microseconds of a core): the pause grows while nothing arrives, up to
  // where a worker, holding its next unit already, still never waits.
  auto pause = kProbePause;
  for (;;) {
    const bool worked = driver.receive();
    if (driver.halt() == Halt::No) dealAll(driver);
    driver.tick();
    if (ended(driver.halt())) break;
    watchWorkers(driver);  // every time round, so that a stream of messages never holds back the watch
    if (worked) {
      pause = kProbePause;
      continue;
    }
    std::this_thread::sleep_for(pause);
    pause = std::min(pause * 2, kLongestProbePause);
  }
  return pile_.allFinished();
}

bool WorkDealer::ended(Halt halt) const {
  return pile_.allFinished() || halt == Halt::Now || (halt == Halt::AfterHeld && nothingHeld());
}

void WorkDealer::dealAll(Dealing& driver) {
  const auto now = Clock::now();
  const auto patience = driver.patience();
  for (int r = 1; r < watch_.ranks(); ++r)
    if (!dealTo(driver, r, now, patience)) return;
  // Rank 0's own render comes last: a worker's unit has further to go.
  if (rules_.dealsRankZero) dealTo(driver, 0, now, patience);
}

bool WorkDealer::dealTo(Dealing& driver, int rank, Clock::time_point now,
                        const std::optional<Clock::duration>& patience) {
  const auto r = static_cast<std::size_t>(rank);
  while (!watch_.lost(rank) && held_[r] < rules_.depth) {
    if (driver.halt() != Halt::No) return false;
    if (rank != 0 && patience && watch_.owedLongerThan(rank, now, *patience)) return true;
    const auto next = pile_.next();
    if (!next) return true;
    if (!driver.ready(*next)) return false;
    const auto unit = pile_.take(rank);
    if (!unit) return true;  // rank 0's own thread took the last one meanwhile
    watch_.dealt(rank, now);
    held_[r] += driver.weight(*unit);
    driver.send(rank, *unit);
    watch_.sent(rank);
  }
  return true;
}

void WorkDealer::release(int rank, int weight) {
  int& held = held_[static_cast<std::size_t>(rank)];
  held = std::max(0, held - weight);
}

void WorkDealer::heard(int worker) {
  if (!watch_.lost(worker)) watch_.heard(worker, held(worker) > 0);
}

void WorkDealer::lose(Dealing& driver, int worker, int why) {
  if (!watch_.lose(worker, why)) return;
  releaseAll(worker);
  driver.lost(worker, why, pile_.reclaim(worker));
}

bool WorkDealer::nothingHeld() const {
  return std::all_of(held_.begin(), held_.end(), [](int weight) { return weight == 0; });
}

void WorkDealer::watchWorkers(Dealing& driver) {
  const auto now = Clock::now();
  const auto patience = driver.patience();
  const bool noneToDeal = !pile_.next();
  for (int w = 1; w < watch_.ranks(); ++w) {
    if (watch_.lost(w)) continue;
    if (watch_.owedLongerThan(w, now, rules_.silentAfter)) {
      lose(driver, w, WorkerWatch::kSilent);
    } else if (patience && noneToDeal && watch_.owedLongerThan(w, now, *patience)) {
      // The end of the work waits only for a worker that is late: its units go to whoever is free (rank 0's own
      // thread first), and the first to finish a unit gives its result. One only slow may still win.
      pile_.reclaim(w);
    } else if (rules_.nudges && !watch_.owes(w) && watch_.unsentLongerThan(w, now, rules_.nudgeEvery)) {
      driver.nudge(w);
      watch_.sent(w);
    }
  }
  dealAll(driver);
}

}  // namespace rayview::cluster
