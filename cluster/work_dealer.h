#pragma once
// The one loop that deals work to the ranks of a distributed render, for tiles and whole frames
// (tile_coordinator.cpp), a batch's scenes (scene_batch.cpp) and the viewer's passes (viewer_farm.cpp): units
// out, results in, silent or dead workers handled once. It holds the unit pile, what each worker holds, and the
// watch on the workers; a driver (Dealing) supplies what differs: how a unit is sent, how what arrived is read and
// kept, and its own rules. No MPI: the driver does the messaging.

#include <chrono>
#include <cstddef>
#include <optional>
#include <vector>

#include "link_times.h"
#include "unit_pile.h"
#include "worker_watch.h"

namespace rayview::cluster {

// When a driver wants the loop to end before every unit is finished.
enum class Halt {
  No,         // go on
  AfterHeld,  // deal nothing more; end once no rank holds a unit (the units dealt are finished first)
  Now,        // end at once
};

struct DealRules {
  int depth = 2;               // the weight of the units a rank holds at once
  bool dealsRankZero = false;  // rank 0 is dealt units by the loop, after the workers (else it takes them itself)
  bool nudges = true;          // an idle worker hears from rank 0 every nudgeEvery
  WorkerWatch::Clock::duration silentAfter = kLostAfter;  // a worker owing an answer this long is lost
  WorkerWatch::Clock::duration nudgeEvery = kNudgeEvery;
};

// What a driver of the loop supplies. Called only from the thread that runs the loop.
class Dealing {
 public:
  using Clock = WorkerWatch::Clock;
  virtual ~Dealing() = default;

  // Hands `unit` to `rank` (rank 0: its own render, with DealRules::dealsRankZero).
  virtual void send(int rank, std::size_t unit) = 0;
  // Reads what arrived (rank 0's own results, a message) and reports it to the dealer (finish, release, heard,
  // lose); true when anything did.
  virtual bool receive() = 0;
  // Tells an idle worker that rank 0 is alive.
  virtual void nudge(int /*worker*/) {}
  // `worker` was lost for `why` (WorkerWatch::kSilent: it owed an answer for DealRules::silentAfter); `units`, the
  // ones it held, are back in the pile for the others.
  virtual void lost(int /*worker*/, int /*why*/, const std::vector<std::size_t>& /*units*/) {}
  virtual Halt halt() { return Halt::No; }
  // Whether `unit`, the next in the pile, may be dealt yet: the dealing waits for it (units go in order).
  virtual bool ready(std::size_t /*unit*/) { return true; }
  // What `unit` weighs against DealRules::depth.
  virtual int weight(std::size_t /*unit*/) { return 1; }
  // Once each time round the loop, after the dealing.
  virtual void tick() {}
  // How long a worker may owe an answer before it is late: then it is dealt nothing new and, once the pile is
  // empty, the units it holds are dealt again to free ranks, the first result of a unit winning (it keeps them and
  // may still win). nullopt: a worker's units go to others only when it is lost.
  virtual std::optional<Clock::duration> patience() { return std::nullopt; }
};

class WorkDealer {
 public:
  using Clock = WorkerWatch::Clock;

  // `units` to deal to `watch.ranks()` ranks; `watch` may outlive the dealer (the viewer's passes share one).
  WorkDealer(std::size_t units, WorkerWatch& watch, DealRules rules);

  // Deals until every unit is finished or the driver halts. True when every unit was finished.
  bool run(Dealing& driver);

  // For the driver's receive and rank 0's own render thread:
  UnitPile& pile() { return pile_; }
  WorkerWatch& watch() { return watch_; }
  // `unit` finished (by anyone): true the first time, when its result is to be kept.
  bool finish(std::size_t unit) { return pile_.finish(unit); }
  // `rank` holds a unit of `weight` no more (its result came, kept or not); releaseAll: it holds nothing any more.
  void release(int rank, int weight = 1);
  void releaseAll(int rank) { held_[static_cast<std::size_t>(rank)] = 0; }
  // A word from `worker`, after what it said was taken: what it still holds is owed from now.
  void heard(int worker);
  // `worker` is lost for `why`: its units go back to the pile and the driver hears of it, once.
  void lose(Dealing& driver, int worker, int why);
  int held(int rank) const { return held_[static_cast<std::size_t>(rank)]; }
  bool nothingHeld() const;

  // One round of dealing to every rank that may take more (exposed for the tests).
  void dealAll(Dealing& driver);
  // Silent workers lost, late ones' units dealt again, idle ones nudged, then dealAll (exposed for the tests).
  void watchWorkers(Dealing& driver);

 private:
  // Deals `rank` up to its depth; false when the dealing is to stop for every rank (the next unit is not ready).
  bool dealTo(Dealing& driver, int rank, Clock::time_point now, const std::optional<Clock::duration>& patience);
  bool ended(Halt halt) const;

  UnitPile pile_;
  WorkerWatch& watch_;
  DealRules rules_;
  std::vector<int> held_;  // per rank: the weight of the units it holds
};

}  // namespace rayview::cluster
