// The one loop that deals work to the ranks (cluster/work_dealer.h), driven by a pretend cluster without MPI: each
// rank holds no more than its depth, a silent rank's units go to the others once, a late rank's units are dealt
// again and the first result of each is the one kept, and the loop ends when every unit is finished.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <deque>
#include <set>
#include <utility>
#include <vector>

#include "work_dealer.h"

namespace rayview::cluster {
namespace {

using namespace std::chrono_literals;

// Ranks that answer what they are sent, one result per receive, in the order sent; a silent rank never answers, a
// late one answers only when the test hands its results over.
class PretendCluster final : public Dealing {
 public:
  PretendCluster(WorkDealer& dealer, std::size_t units, int ranks)
      : keptFrom(units, -1), sent(static_cast<std::size_t>(ranks)), mostHeld(static_cast<std::size_t>(ranks), 0),
        mostInFlight(static_cast<std::size_t>(ranks), 0), dealer_(dealer) {}

  void send(int rank, std::size_t unit) override {
    sent[rank].push_back(unit);
    inFlight_.emplace_back(rank, unit);
    mostHeld[rank] = std::max(mostHeld[rank], dealer_.held(rank));
    const auto count = std::count_if(inFlight_.begin(), inFlight_.end(), [&](const auto& u) { return u.first == rank; });
    mostInFlight[rank] = std::max(mostInFlight[rank], static_cast<int>(count));
  }

  bool receive() override {
    const auto answer = std::find_if(inFlight_.begin(), inFlight_.end(), [&](const auto& u) {
      return u.first != silentRank && u.first != lateRank;
    });
    if (answer == inFlight_.end()) return false;
    const auto [rank, unit] = *answer;
    inFlight_.erase(answer);
    result(rank, unit);
    return true;
  }

  // The late rank's results, now.
  void lateResultsArrive() {
    for (auto it = inFlight_.begin(); it != inFlight_.end();) {
      if (it->first != lateRank) {
        ++it;
        continue;
      }
      result(it->first, it->second);
      it = inFlight_.erase(it);
    }
  }

  void lost(int worker, int why, const std::vector<std::size_t>& units) override {
    losses.push_back({worker, why, units});
  }
  int weight(std::size_t /*unit*/) override { return unitWeight; }
  std::optional<Clock::duration> patience() override { return latePatience; }

  struct Loss {
    int worker;
    int why;
    std::vector<std::size_t> units;
  };

  int silentRank = -1;
  int lateRank = -1;
  int unitWeight = 1;
  std::optional<Clock::duration> latePatience;
  std::vector<int> keptFrom;  // per unit: the rank whose result was kept
  std::vector<std::vector<std::size_t>> sent;  // per rank: the units it was dealt, in order
  std::vector<int> mostHeld, mostInFlight;     // per rank
  std::vector<Loss> losses;

 private:
  void result(int rank, std::size_t unit) {
    dealer_.release(rank, unitWeight);
    if (dealer_.finish(unit)) {
      EXPECT_EQ(keptFrom[unit], -1) << "unit " << unit << " kept twice";
      keptFrom[unit] = rank;
    }
    dealer_.heard(rank);
  }

  WorkDealer& dealer_;
  std::deque<std::pair<int, std::size_t>> inFlight_;
};

DealRules quietRules(int depth) {
  DealRules rules;
  rules.depth = depth;
  rules.dealsRankZero = true;
  rules.nudges = false;
  return rules;
}

TEST(WorkDealer, EveryUnitIsFinishedOnceAndNoRankHoldsMoreThanItsDepth) {
  WorkerWatch watch(3);
  WorkDealer dealer(25, watch, quietRules(2));
  PretendCluster cluster(dealer, 25, 3);
  EXPECT_TRUE(dealer.run(cluster));
  for (int from : cluster.keptFrom) EXPECT_NE(from, -1);
  for (int r = 0; r < 3; ++r) {
    EXPECT_EQ(cluster.mostHeld[r], 2) << "rank " << r;
    EXPECT_EQ(cluster.mostInFlight[r], 2) << "rank " << r;
    EXPECT_EQ(dealer.held(r), 0);
  }
  // Rank 0 is dealt last of the idle ranks: the workers get the first units.
  EXPECT_EQ(cluster.sent[1].front(), 0u);
  EXPECT_EQ(cluster.sent[0].front(), 4u);
  EXPECT_TRUE(cluster.losses.empty());
}

TEST(WorkDealer, AUnitThatWeighsTheDepthIsARanksOnlyOne) {
  WorkerWatch watch(2);
  WorkDealer dealer(6, watch, quietRules(2));
  PretendCluster cluster(dealer, 6, 2);
  cluster.unitWeight = 2;  // a whole frame among tiles
  EXPECT_TRUE(dealer.run(cluster));
  EXPECT_EQ(cluster.mostInFlight[1], 1);
  EXPECT_EQ(cluster.mostInFlight[0], 1);
}

TEST(WorkDealer, ASilentRanksUnitsAreDealtToTheOthersOnce) {
  WorkerWatch watch(3);
  DealRules rules = quietRules(2);
  rules.silentAfter = 30ms;
  WorkDealer dealer(8, watch, rules);
  PretendCluster cluster(dealer, 8, 3);
  cluster.silentRank = 2;
  const auto start = std::chrono::steady_clock::now();
  EXPECT_TRUE(dealer.run(cluster));
  EXPECT_GE(std::chrono::steady_clock::now() - start, 30ms);  // it was waited for as long as the rules say
  ASSERT_EQ(cluster.losses.size(), 1u);
  EXPECT_EQ(cluster.losses[0].worker, 2);
  EXPECT_EQ(cluster.losses[0].why, WorkerWatch::kSilent);
  EXPECT_EQ(cluster.losses[0].units, cluster.sent[2]);
  EXPECT_EQ(cluster.sent[2].size(), 2u);
  EXPECT_TRUE(watch.lost(2));
  EXPECT_EQ(watch.lostRanks(), (std::vector<bool>{false, false, true}));
  // Its units were finished by the survivors, each once.
  for (std::size_t unit : cluster.sent[2]) EXPECT_NE(cluster.keptFrom[unit], 2);
  for (int from : cluster.keptFrom) EXPECT_NE(from, -1);
}

TEST(WorkDealer, ALateRanksUnitsAreDealtAgainAndTheFirstResultWins) {
  WorkerWatch watch(3);
  WorkDealer dealer(4, watch, quietRules(2));
  PretendCluster cluster(dealer, 4, 3);
  cluster.lateRank = 2;
  cluster.latePatience = 5ms;
  EXPECT_TRUE(dealer.run(cluster));
  const std::vector<std::size_t> lateUnits = cluster.sent[2];
  ASSERT_EQ(lateUnits.size(), 2u);
  // Once nothing was left to deal, the late rank's units went to a free rank, whose results were kept; the late
  // rank was not lost for it, and was dealt nothing new while late.
  auto dealtTo = [&](int rank, std::size_t unit) {
    return std::find(cluster.sent[rank].begin(), cluster.sent[rank].end(), unit) != cluster.sent[rank].end();
  };
  for (std::size_t unit : lateUnits) {
    EXPECT_TRUE(dealtTo(0, unit) || dealtTo(1, unit)) << "unit " << unit;
    EXPECT_NE(cluster.keptFrom[unit], 2);
  }
  EXPECT_FALSE(watch.lost(2));
  EXPECT_TRUE(cluster.losses.empty());
  // Its own results, arriving now, are second and not kept.
  const std::vector<int> kept = cluster.keptFrom;
  cluster.lateResultsArrive();
  EXPECT_EQ(cluster.keptFrom, kept);
  EXPECT_EQ(dealer.held(2), 0);
  EXPECT_FALSE(watch.owes(2));
}

TEST(WorkDealer, AHaltAfterHeldDealsNoMoreAndEndsOnceNothingIsHeld) {
  class Halting final : public Dealing {
   public:
    explicit Halting(WorkDealer& dealer) : dealer_(dealer) {}
    void send(int rank, std::size_t unit) override { held.emplace_back(rank, unit), ++dealt; }
    bool receive() override {
      if (held.empty()) return false;
      halted = true;  // the first result stops the dealing; what is held is still finished
      const auto [rank, unit] = held.front();
      held.pop_front();
      dealer_.release(rank);
      dealer_.finish(unit);
      dealer_.heard(rank);
      return true;
    }
    Halt halt() override { return halted ? Halt::AfterHeld : Halt::No; }
    std::deque<std::pair<int, std::size_t>> held;
    int dealt = 0;
    bool halted = false;

   private:
    WorkDealer& dealer_;
  };
  WorkerWatch watch(3);
  WorkDealer dealer(10, watch, quietRules(1));
  Halting driver(dealer);
  EXPECT_FALSE(dealer.run(driver));
  EXPECT_EQ(driver.dealt, 3);  // one each before the halt, none after
  EXPECT_EQ(dealer.pile().finished(), 3u);
  EXPECT_TRUE(dealer.nothingHeld());
}

TEST(WorkDealer, TheNextUnitNotReadyHoldsBackTheDealing) {
  class Gated final : public Dealing {
   public:
    explicit Gated(WorkDealer& dealer) : dealer_(dealer) {}
    void send(int rank, std::size_t unit) override { order.emplace_back(rank, unit); }
    bool receive() override {
      ++rounds;
      for (const auto& [rank, unit] : order)
        if (dealer_.finish(unit)) {
          dealer_.release(rank);
          dealer_.heard(rank);
          return true;
        }
      return false;
    }
    bool ready(std::size_t unit) override { return static_cast<int>(unit) < rounds; }  // one more unit a round
    std::vector<std::pair<int, std::size_t>> order;
    int rounds = 0;

   private:
    WorkDealer& dealer_;
  };
  WorkerWatch watch(2);
  WorkDealer dealer(3, watch, quietRules(1));
  Gated driver(dealer);
  EXPECT_TRUE(dealer.run(driver));
  ASSERT_EQ(driver.order.size(), 3u);
  for (std::size_t k = 0; k < 3; ++k) EXPECT_EQ(driver.order[k].second, k);  // in the pile's order
}

}  // namespace
}  // namespace rayview::cluster
