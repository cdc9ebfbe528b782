// The preview level a restart starts with, from made-up pass times: what the user sees while dragging.
#include <gtest/gtest.h>

#include <vector>

#include "rayview/preview_level.h"

namespace rayview {
namespace {

// The final pass of a full refinement: the pixels the stride-2 pass before it did not trace (3/4 of them).
PassTime finalPass(int width, int height, double ms) {
  return {1, levelPixels(width, height, 1) - levelPixels(width, height, 2), ms, true};
}

// A drag move's one pass at `stride`, the first of its restart: every pixel of that level.
PassTime dragPass(int width, int height, int stride, double ms, bool complete = true) {
  return {stride, levelPixels(width, height, stride), ms, complete};
}

int dragLevel(const std::vector<PassTime>& recent, int width, int height) {
  return choosePreviewStride(recent, width, height, kDragPassBudgetMs);
}

TEST(PreviewLevel, LevelPixelsCountPartialBlocksAtTheEdges) {
  EXPECT_EQ(levelPixels(37, 23, 1), 37 * 23);
  EXPECT_EQ(levelPixels(37, 23, 16), 3 * 2);
  EXPECT_EQ(levelPixels(6400, 4000, 64), 100 * 63);
  EXPECT_EQ(levelPixels(1, 1, 64), 1);
  EXPECT_EQ(levelPixels(0, 10, 1), 0);
}

TEST(PreviewLevel, NothingMeasuredStartsAtTheDefaultLevel) {
  EXPECT_EQ(dragLevel({}, 512, 512), kUnmeasuredStride);
  EXPECT_EQ(dragLevel({{4, 0, 3.0, true}}, 512, 512), kUnmeasuredStride);  // a pass of nothing tells nothing
}

TEST(PreviewLevel, ASceneWhoseFullPassTakes5MsIsDraggedAtFullResolution) {
  EXPECT_EQ(dragLevel({finalPass(512, 512, 5.0 * 0.75)}, 512, 512), 1);
  // And stays there: the next move's full pass measured 5 ms.
  EXPECT_EQ(dragLevel({finalPass(512, 512, 3.75), dragPass(512, 512, 1, 5.0)}, 512, 512), 1);
}

TEST(PreviewLevel, ASceneWhoseFullPassTakesAFrameAndMoreIsDraggedAtHalfResolution) {
  // Full resolution would take 24 ms; half, 6 ms.
  EXPECT_EQ(dragLevel({finalPass(512, 512, 18.0)}, 512, 512), 2);
  EXPECT_EQ(dragLevel({finalPass(512, 512, 18.0), dragPass(512, 512, 2, 6.0)}, 512, 512), 2);
}

TEST(PreviewLevel, AHugeImageGoesAsCoarseAsItsMeasuredCostNeeds) {
  // 6400x4000, a heavy scene: the final pass's 19.2 Mpixels took 6 s. 1/16 would take 31 ms, 1/32 8 ms.
  const std::vector<PassTime> heavy{finalPass(6400, 4000, 6000.0)};
  EXPECT_EQ(dragLevel(heavy, 6400, 4000), 32);
  // A light one (2 s): 1/16 takes 10 ms.
  EXPECT_EQ(dragLevel({finalPass(6400, 4000, 2000.0)}, 6400, 4000), 16);
  // So heavy that even 1/32 misses the frame: 1/64 (100x63 pixels).
  EXPECT_EQ(dragLevel({finalPass(6400, 4000, 20000.0)}, 6400, 4000), 64);
}

TEST(PreviewLevel, OneMeasuredLevelPredictsTheOthersByPixelCount) {
  // Measured on a 512x512 image, asked for the same cost per pixel at 6400x4000 (a resolution edit): 98 times
  // the pixels, so 1/8 (8 ms) rather than full resolution.
  const std::vector<PassTime> small{finalPass(512, 512, 3.75)};
  EXPECT_EQ(dragLevel(small, 512, 512), 1);
  EXPECT_EQ(dragLevel(small, 6400, 4000), 8);
}

TEST(PreviewLevel, TheNewestCompletePassCountsNotOlderOnes) {
  // Cheap at full resolution before the drag; the view the drag reached costs 15 ms at 1/4.
  const std::vector<PassTime> recent{finalPass(512, 512, 3.75), dragPass(512, 512, 4, 15.0)};
  EXPECT_EQ(dragLevel(recent, 512, 512), 4);
}

TEST(PreviewLevel, APassCancelledAfterRunningLongMakesItCoarser) {
  std::vector<PassTime> recent{dragPass(512, 512, 2, 4.0)};
  ASSERT_EQ(dragLevel(recent, 512, 512), 2);
  // The next move's pass at 1/2 had run 40 ms when the move after it cancelled it: at least 10 times the cost.
  recent.push_back(dragPass(512, 512, 2, 40.0, false));
  EXPECT_EQ(dragLevel(recent, 512, 512), 4);
}

TEST(PreviewLevel, APassCancelledSoonAfterItStartedChangesNothing) {
  const std::vector<PassTime> recent{dragPass(512, 512, 2, 4.0), dragPass(512, 512, 1, 0.1, false)};
  EXPECT_EQ(dragLevel(recent, 512, 512), 2);
}

TEST(PreviewLevel, CancelledPassesAloneNeverGoFinerThanTheDefault) {
  EXPECT_EQ(dragLevel({dragPass(64, 64, 16, 0.01, false)}, 64, 64), kUnmeasuredStride);
  // A first pass of 16 pixels that had run 100 ms: no level but the coarsest fits.
  EXPECT_EQ(dragLevel({dragPass(64, 64, 16, 100.0, false)}, 64, 64), kCoarsestStride);
}

TEST(PreviewLevel, GoingFinerNeedsRoomToSpareStayingDoesNot) {
  // At 1/2, 3.9 ms predicts 15.6 ms at full resolution: within 16, but a prediction from a quarter of the
  // pixels; it is not taken, so the level does not flip on the next move's noise.
  EXPECT_EQ(dragLevel({dragPass(512, 512, 2, 3.9)}, 512, 512), 2);
  EXPECT_EQ(dragLevel({dragPass(512, 512, 2, 2.9)}, 512, 512), 1);
  // Measured at full resolution itself, 15.6 ms fits.
  EXPECT_EQ(dragLevel({dragPass(512, 512, 1, 15.6)}, 512, 512), 1);
}

TEST(PreviewLevel, AWholeFrameWithin12MsIsAnEditsFirstPass) {
  // Measured at full resolution: 11 ms goes first as it is; 13 ms starts with a preview, at 1/8 although 1/2
  // would fit the 8 ms budget (a finer preview delays the final pass more than it shows).
  EXPECT_EQ(chooseEditStride(std::vector<PassTime>{dragPass(512, 512, 1, 11.0)}, 512, 512), 1);
  EXPECT_EQ(chooseEditStride(std::vector<PassTime>{dragPass(512, 512, 1, 13.0)}, 512, 512), kFinestEditPreviewStride);
  // Predicted from a coarser pass, the margin of kRefineShare applies (12 * 0.75 = 9 ms).
  EXPECT_EQ(chooseEditStride(std::vector<PassTime>{dragPass(512, 512, 2, 8.5 / 4)}, 512, 512), 1);
  EXPECT_EQ(chooseEditStride(std::vector<PassTime>{dragPass(512, 512, 2, 10.0 / 4)}, 512, 512), 8);
  // A heavy frame: the budget decides (1 s at full resolution: 1/16 takes ~4 ms, 1/8 ~16 ms).
  EXPECT_EQ(chooseEditStride(std::vector<PassTime>{dragPass(512, 512, 1, 1000.0)}, 512, 512), 16);
}

TEST(PreviewLevel, AfterTheFirstPassComesFullResolutionWithOneLevelBetweenOnlyForVeryCoarseStarts) {
  EXPECT_EQ(nextPassStride(2, 2), 1);
  EXPECT_EQ(nextPassStride(8, 8), 1);
  EXPECT_EQ(nextPassStride(16, 16), 4);
  EXPECT_EQ(nextPassStride(16, 4), 1);
  EXPECT_EQ(nextPassStride(64, 64), 4);
  EXPECT_EQ(nextPassStride(64, 4), 1);
  EXPECT_EQ(nextPassStride(4, 1), 0);
  EXPECT_EQ(nextPassStride(1, 1), 0);
}

TEST(PreviewLevel, AnEditsFirstPassHasHalfTheBudgetOfADragMove) {
  // Full resolution takes 16 ms: a drag shows it; an edit starts at 1/2 (4 ms) and refines.
  const std::vector<PassTime> recent{dragPass(512, 512, 1, 16.0)};
  EXPECT_EQ(choosePreviewStride(recent, 512, 512, kDragPassBudgetMs), 1);
  EXPECT_EQ(choosePreviewStride(recent, 512, 512, kFirstPassBudgetMs), 2);
}

}  // namespace
}  // namespace rayview
