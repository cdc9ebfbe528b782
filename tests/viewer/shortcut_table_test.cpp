// The shortcut table (ui/shortcut_table.cpp) is what the keys do and what the help lists; the whole render's
// progress with several samples per pixel (ui/render_progress.cpp). Part of viewer_logic_test.
#include <chrono>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include "navigation_input.h"
#include "render_progress.h"
#include "shortcut_table.h"

namespace rayview {
namespace {

Shortcuts press(int key, int mods, bool fieldHasKeyboard = false) {
  NavigationInput input;
  Shortcuts shortcuts;
  InputEvent e;
  e.kind = InputEvent::Kind::Key;
  e.key = key;
  e.mods = mods;
  e.pressed = true;
  input.handle({e}, false, fieldHasKeyboard, 600.0, 600.0, nullptr, shortcuts);
  return shortcuts;
}

TEST(ShortcutTable, EachKeyDoesWhatItsRowSays) {
  int keyed = 0;
  for (const ShortcutRow& row : shortcutTable()) {
    if (!row.action) continue;
    for (const int key : row.keys) {
      if (key == 0) continue;
      Shortcuts expected;
      row.action(expected);
      const Shortcuts got = press(key, row.mods);
      // Every field a row can set, compared: the key did that and nothing else.
      EXPECT_EQ(got.toggleHelp, expected.toggleHelp) << row.input << " key " << key;
      EXPECT_EQ(got.saveFrame, expected.saveFrame) << row.input;
      EXPECT_EQ(got.saveScene, expected.saveScene) << row.input;
      EXPECT_EQ(got.undo, expected.undo) << row.input;
      EXPECT_EQ(got.redo, expected.redo) << row.input;
      EXPECT_EQ(got.frameScene, expected.frameScene) << row.input;
      EXPECT_EQ(got.frameAll, expected.frameAll) << row.input;
      EXPECT_EQ(got.exposureSteps, expected.exposureSteps) << row.input;
      EXPECT_EQ(got.imageZoomBy, expected.imageZoomBy) << row.input;
      EXPECT_EQ(got.quit, expected.quit) << row.input;
      ++keyed;
    }
  }
  EXPECT_GE(keyed, 25);
}

TEST(ShortcutTable, TheHelpNamesEveryRowThatDoesSomething) {
  // A row without a name of its own is a second key of the row above it, which names both.
  std::string previous;
  std::set<std::pair<int, int>> seen;
  for (const ShortcutRow& row : shortcutTable()) {
    if (row.input[0] != '\0') {
      previous = row.input;
      EXPECT_NE(std::string(row.does), "") << row.input;
    }
    EXPECT_FALSE(previous.empty()) << "the first row must have a name";
    for (const int key : row.keys)
      if (key != 0) {
        EXPECT_TRUE(seen.insert({key, row.mods}).second) << "two rows for one key: " << previous;
      }
  }
  for (const char* named : {"F1 or ?", "Home", "F", "F11", "V", "1", "0", "+, -", "E, Shift+E", "D", "hold Space",
                            "double-click", "Ctrl+Z", "Ctrl+Shift+Z, Ctrl+Y"}) {
    bool found = false;
    for (const ShortcutRow& row : shortcutTable()) found |= std::string(row.input) == named;
    EXPECT_TRUE(found) << named << " is not in the help";
  }
}

TEST(ShortcutTable, ModifiersAndFieldsAreAsTheRowsSay) {
  EXPECT_TRUE(press(GLFW_KEY_SLASH, GLFW_MOD_SHIFT).toggleHelp) << "? is Shift+/";
  EXPECT_FALSE(press(GLFW_KEY_SLASH, 0).toggleHelp);
  EXPECT_TRUE(press(GLFW_KEY_F1, 0).toggleHelp);
  EXPECT_EQ(press(GLFW_KEY_E, GLFW_MOD_SHIFT).exposureSteps, -1);
  EXPECT_TRUE(press(GLFW_KEY_EQUAL, GLFW_MOD_SHIFT).imageZoomBy == 2.0) << "+ is Shift+= on most keyboards";
  EXPECT_FALSE(press(GLFW_KEY_F, GLFW_MOD_CONTROL).frameScene);
  EXPECT_TRUE(press(GLFW_KEY_Z, GLFW_MOD_CONTROL | GLFW_MOD_SHIFT).redo);
  EXPECT_FALSE(press(GLFW_KEY_Z, GLFW_MOD_CONTROL | GLFW_MOD_SHIFT).undo);
  // A letter typed into a field is the field's; Ctrl+S and the F-keys still work there.
  EXPECT_FALSE(press(GLFW_KEY_F, 0, true).frameScene);
  EXPECT_FALSE(press(GLFW_KEY_Z, GLFW_MOD_CONTROL, true).undo);
  EXPECT_TRUE(press(GLFW_KEY_S, GLFW_MOD_CONTROL, true).saveFrame);
  EXPECT_TRUE(press(GLFW_KEY_F1, 0, true).toggleHelp);
}

TEST(RenderProgress, SixteenSamplesShowDoneOfTotalAndTimeLeft) {
  using namespace std::chrono_literals;
  RenderProgressEstimate estimate;
  const auto t0 = RenderProgressEstimate::Clock::time_point{} + 100s;
  estimate.update(7, 0, 16, 0.0, t0);
  // Two samples and a half in one second: 13.5 to go at that rate.
  const RenderProgress p = estimate.update(7, 2, 16, 0.5, t0 + 1s);
  EXPECT_EQ(p.samplesDone, 2);
  EXPECT_EQ(p.samplesTotal, 16);
  EXPECT_NEAR(p.renderFraction, 2.5 / 16, 1e-9);
  ASSERT_TRUE(p.secondsLeft.has_value());
  EXPECT_NEAR(*p.secondsLeft, 5.4, 1e-9);
  EXPECT_EQ(describeProgress(p), "samples 2/16, 16% of the render, 6 s left");
  // The next sample's pass already running while the frame still says 2: the bar does not go back.
  EXPECT_NEAR(estimate.update(7, 2, 16, 0.1, t0 + 1100ms).renderFraction, 2.5 / 16, 1e-9);
  // A new edit starts over.
  const RenderProgress again = estimate.update(8, 0, 16, 0.0, t0 + 2s);
  EXPECT_EQ(again.renderFraction, 0.0);
  EXPECT_FALSE(again.secondsLeft.has_value());
}

TEST(RenderProgress, OneSampleIsThePassAlone) {
  RenderProgress p;
  p.passFraction = 0.43;
  EXPECT_EQ(describeProgress(p), "full resolution: 43%");
}

}  // namespace
}  // namespace rayview
