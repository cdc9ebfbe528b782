#pragma once
// Timing the renders of the trade-off measurement (tradeoff.cpp). Private to the analysis library.
//
// A render that lasts kMinTimedMs or more is timed alone (renderOnce). A quicker one is timed again and again,
// in turn with the other quick settings, and its fastest time is kept (timeInTurn). Timed once and alone, a sub-millisecond pass (a preview
// level) measured mostly what came before it and around it, not its own work, and the 1/16 level measured
// slower than 1/8 (docs/tradeoff.md, "Time"):
// - the caches the previous setting left: the best image, rendered on the other BVH, came just before the 1/16
//   level, which then took 3 to 6 times as long as right after a render of its own kind (killeroo_2020 at
//   1/4: 0.17-0.31 ms against 0.05 ms);
// - a time slice lost to another process (a few ms, ten times the pass), in a run too short to be judged by
//   its CPU share;
// - handing the pass to the pool's threads: an empty pass took 0.02 to 0.14 ms, in stretches of many passes
//   at either end (whether the other cores must be woken), as much as a tiny pass's whole work. Every pass in the
//   viewer pays it too, so it stays in the time; timed in turn, the settings compared share it.

#include <atomic>
#include <chrono>
#include <span>
#include <vector>

#include "rayview/image.h"
#include "rayview/render_settings.h"
#include "rayview/thread_pool.h"
#include "rayview/tracer.h"

namespace rayview {

using TimingClock = std::chrono::steady_clock;

double msSince(TimingClock::time_point start);
double median(std::vector<double> values);

// The shortest render timed alone; its CPU share is judged only from this length on (below it, thread
// wake-up latency alone can halve the share).
inline constexpr double kMinTimedMs = 20.0;
// Quick settings are timed in turn at least this many times each (and for at least kMinTimedMs in all).
inline constexpr int kMinTurns = 5;

struct TimedRun {
  Image image;            // the pass as the viewer shows it: each pixel the sample at the top-left of its block
  RayCounts rays;
  double wallMs = 0.0;
  double cpuShare = 1.0;  // CPU time / (wall time x threads); well below 1 when other processes ran
};

// Renders the pixels on the stride grid once, timed (the block fill after it is not), on `pool`. False when
// `cancel` was raised.
bool renderOnce(const Tracer& tracer, int width, int height, int stride, ThreadPool& pool,
                const std::atomic<bool>* cancel, TimedRun& run);

struct QuickRender {
  const Tracer* tracer = nullptr;
  int stride = 1;
  AccelKind accel = AccelKind::Embree;  // the BVH it traverses
};

// Renders each of `renders` in turn, grouped by BVH, each render timed, until each has been timed kMinTurns
// times and the whole has lasted kMinTimedMs. After a change of BVH (and first) an untimed render comes
// before the timed one, so that every timed render follows one on its own BVH. Returns each one's fastest
// time, in the order given; nothing when `cancel` was raised. The fastest, not the median: other processes
// only ever add time, and on a busy machine (load 10 on 2 cores) more than half of a tiny pass's renders
// lost a time slice; the fastest is the render's own cost, as a long render's time is once a run slowed
// by other processes has been repeated.
std::vector<double> timeInTurn(std::span<const QuickRender> renders, int width, int height, ThreadPool& pool,
                               const std::atomic<bool>* cancel);

}  // namespace rayview
