#pragma once
// Which preview level a restart starts with, judged from the passes just measured.
//
// A level is a pixel stride: a pass at stride s traces one pixel per s x s block. A pixel costs about the same
// at every level, so the newest measured pass predicts each level's time from its pixel count, whatever the
// image size. The first pass of a restart is the finest level predicted to fit a budget. Pure: the progressive
// renderer keeps the measurements and asks at each restart; the tests hand it made-up times.

#include <cstdint>
#include <span>

namespace rayview {

// The levels: the powers of two from 1 (full resolution) to this. 64 keeps a 6400x4000 image's first pass
// at 100x63 pixels, which even a heavy scene traces within a 60 Hz frame on two threads.
inline constexpr int kCoarsestStride = 64;
// The start before anything was measured (a renderer's first restart).
inline constexpr int kUnmeasuredStride = 16;
// An edit's first pass takes about this long, so it shows within a 60 Hz frame while finer passes follow.
inline constexpr double kFirstPassBudgetMs = 8.0;
// While the user drags, each move shows one pass and nothing finer: the finest that fits a 60 Hz frame.
inline constexpr double kDragPassBudgetMs = 16.0;
// A level finer than the newest measured one must be predicted within this share of the budget: scaled up
// from a smaller pass, the prediction carries that pass's noise, and a level that flips on every move flickers.
inline constexpr double kRefineShare = 0.75;

struct PassTime {
  int stride = 1;
  std::int64_t pixels = 0;  // traced by the pass (for a cancelled one: that it would have traced)
  double ms = 0.0;          // how long it took, or ran before it was cancelled
  bool complete = true;     // false: cancelled, so its pixels cost at least ms / pixels each
};

// The pixels a first pass at `stride` traces: one per stride x stride block of a width x height image (the
// blocks at the right and bottom edges may be partial).
std::int64_t levelPixels(int width, int height, int stride);

// An edit's whole frame predicted within this is traced first, with no preview level before it: the preview
// would only delay it (half a 60 Hz frame's budget beyond kFirstPassBudgetMs, so the first pass still shows
// within 16 ms).
inline constexpr double kWholeFrameFirstPassMs = 12.0;
// An edit's preview level is never finer than this (unless the whole frame goes first): a preview pass's
// pixels cost 1.5 to 2.7 times what they cost in the full pass (see nextPassStride), so a preview at 1/4 (a
// sixteenth of the pixels) delayed the final pass by up to 16 %, one at 1/8 by at most ~3 %. A preview that
// fine only shows for the few milliseconds before the final pass anyway.
inline constexpr int kFinestEditPreviewStride = 8;
// The one level between a first pass at kIntermediateAfter or coarser and the full-resolution pass.
inline constexpr int kIntermediateStride = 4;
inline constexpr int kIntermediateAfter = 16;

// The stride to start with: the finest level whose predicted time fits `budgetMs`, else kCoarsestStride.
// `recent` is oldest first. The newest complete pass gives the cost per pixel; a pass cancelled after it
// that had already run longer can only raise that cost. With no complete pass, never finer than
// kUnmeasuredStride.
int choosePreviewStride(std::span<const PassTime> recent, int width, int height, double budgetMs);

// An edit's first stride: 1 when the whole frame is predicted within kWholeFrameFirstPassMs, else
// choosePreviewStride with kFirstPassBudgetMs, and never finer than kFinestEditPreviewStride.
int chooseEditStride(std::span<const PassTime> recent, int width, int height);

// The stride of the pass after one at `stride` (0 after full resolution), in a restart whose first pass was at
// `firstStride`. After the first pass comes the full-resolution one, with one level at kIntermediateStride
// between them only when the first was at kIntermediateAfter or coarser (large images, heavy scenes: there
// the final pass takes seconds). Each level between costs: a pixel of a sparse pass costs 1.5 to 2.7 times
// what it costs in a full pass (incoherent packets, cold caches; measured on car and killeroo_2020 with
// edit_latency_bench), and halving level by level made an edit's final pass come 12-40 % later than the
// headless render of the same image (docs/PERFORMANCE.md, "The viewer's progressive passes").
int nextPassStride(int firstStride, int stride);

}  // namespace rayview
