// placeOverlays: the overlays over the image area never cover one another, stay inside the area (never over the
// panels), and the stats keep clear of the picked mesh and the difference view when there is room elsewhere.
#include <gtest/gtest.h>

#include <vector>

#include "overlay_layout.h"

namespace rayview {
namespace {

// Sizes as the default font measures the longest texts (window units at content scale 1).
constexpr OverlaySize kStatsBox{372.0f, 237.0f, 17.0f};
constexpr OverlaySize kStatsLine{576.0f, 29.0f, 13.0f};
constexpr OverlaySize kReadout{681.0f, 29.0f, 13.0f};
constexpr OverlaySize kToast{420.0f, 29.0f, 13.0f};
constexpr OverlaySize kLabel{250.0f, 29.0f, 13.0f};

// The image area of a window of this size, right of the panel column (400 wide, at most 45 % of the window).
OverlayRequest requestFor(float windowWidth, float windowHeight) {
  const float panel = std::min(400.0f, windowWidth * 0.45f);
  OverlayRequest q;
  q.view = {panel, 0.0f, windowWidth - panel, windowHeight};
  q.statsBox = kStatsBox;
  q.statsLine = kStatsLine;
  q.readout = kReadout;
  q.toast = kToast;
  q.label = kLabel;
  q.oneLine = windowWidth < 1280.0f || windowHeight < 800.0f;
  return q;
}

std::vector<OverlayRect> placedRects(const OverlayPlacement& p) {
  std::vector<OverlayRect> rects;
  for (const auto* r : {&p.label, &p.toast, &p.stats, &p.readout})
    if (*r) rects.push_back(**r);
  return rects;
}

void expectApartAndInside(const OverlayRequest& q, const OverlayPlacement& p, std::size_t expected) {
  const std::vector<OverlayRect> rects = placedRects(p);
  ASSERT_EQ(rects.size(), expected);
  for (std::size_t i = 0; i < rects.size(); ++i) {
    EXPECT_GE(rects[i].x, q.view.x) << "overlay " << i << " runs over the panels";
    EXPECT_LE(rects[i].right(), q.view.right()) << "overlay " << i;
    EXPECT_GE(rects[i].y, q.view.y) << "overlay " << i;
    EXPECT_LE(rects[i].bottom(), q.view.bottom()) << "overlay " << i;
    for (std::size_t j = i + 1; j < rects.size(); ++j) EXPECT_FALSE(rects[i].intersects(rects[j])) << i << " and " << j;
  }
}

TEST(OverlayLayout, NothingCollidesAtTheWindowSizesUsersHave) {
  for (const auto& [w, h] : {std::pair{800.0f, 600.0f}, std::pair{1000.0f, 640.0f}, std::pair{1280.0f, 800.0f}}) {
    SCOPED_TRACE(std::to_string(static_cast<int>(w)) + "x" + std::to_string(static_cast<int>(h)));
    const OverlayRequest q = requestFor(w, h);
    expectApartAndInside(q, placeOverlays(q), 4);
    // With a load error over the top of the area as well.
    OverlayRequest withError = q;
    withError.topLeftHeight = 90.0f;
    const OverlayPlacement p = placeOverlays(withError);
    expectApartAndInside(withError, p, 4);
    for (const OverlayRect& r : placedRects(p)) EXPECT_GE(r.y, withError.margin + 90.0f - 0.5f) << "under the error";
  }
}

TEST(OverlayLayout, TheStatsAreABoxWhereThereIsRoomAndALineWhereNot) {
  const OverlayPlacement large = placeOverlays(requestFor(1280.0f, 800.0f));
  EXPECT_FALSE(large.statsOneLine);
  EXPECT_FLOAT_EQ(large.stats->width, kStatsBox.width);
  // At 800x600 the one line is wider than the 440-wide area: wrapped to it, not run over the panels.
  const OverlayRequest small = requestFor(800.0f, 600.0f);
  const OverlayPlacement p = placeOverlays(small);
  EXPECT_TRUE(p.statsOneLine);
  EXPECT_LE(p.stats->width, small.view.width - 2.0f * small.margin);
  EXPECT_GT(p.stats->height, kStatsLine.height);
}

TEST(OverlayLayout, TheReadoutMovesAboveTheStatsRatherThanUnderThem) {
  const OverlayRequest q = requestFor(1280.0f, 800.0f);
  const OverlayPlacement p = placeOverlays(q);
  EXPECT_LE(p.readout->bottom(), p.stats->y);
  EXPECT_FLOAT_EQ(p.readout->x, q.view.x + q.margin);
}

TEST(OverlayLayout, TheStatsKeepClearOfThePickedMesh) {
  OverlayRequest q = requestFor(1280.0f, 800.0f);
  // A mesh picked in the bottom-right corner, where the box would go.
  q.keepClear = {{1000.0f, 500.0f, 200.0f, 200.0f}};
  const OverlayPlacement p = placeOverlays(q);
  ASSERT_TRUE(p.stats);
  EXPECT_FALSE(p.stats->intersects(q.keepClear[0]));
  expectApartAndInside(q, p, 4);
}

TEST(OverlayLayout, OverTheDifferenceViewTheStatsTakeOneLine) {
  OverlayRequest q = requestFor(1280.0f, 800.0f);
  q.keepClear = {q.view};  // the difference fills the area: nowhere is clear
  const OverlayPlacement p = placeOverlays(q);
  ASSERT_TRUE(p.stats);
  EXPECT_TRUE(p.statsOneLine);
  expectApartAndInside(q, p, 4);
  // A letterboxed image leaves the bottom band clear: the box goes there if it fits, else the line.
  q.keepClear = {{q.view.x, 100.0f, q.view.width, 450.0f}};
  const OverlayPlacement boxed = placeOverlays(q);
  EXPECT_FALSE(boxed.stats->intersects(q.keepClear[0]));
}

}  // namespace
}  // namespace rayview
