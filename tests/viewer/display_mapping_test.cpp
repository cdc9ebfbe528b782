// Exposure and gamma in the viewer, without a window: the mapping of 8-bit values, the image shown per source and
// when it is mapped again, numbered "as displayed" saves, and the `set exposure`, `set gamma` and
// `save-frame-displayed` script commands.
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "automation_script.h"
#include "display_mapping.h"
#include "numbered_file.h"
#include "script_runner.h"
#include "viewer_fixtures.h"

namespace rayview {
namespace {

using namespace viewer_testing;

std::uint8_t shown(int level, float stops, float gamma) {
  return displayLevel(static_cast<std::uint8_t>(level), DisplayMapping{stops, gamma});
}

// ----------------------------------------------------------------------------------------------- levels

TEST(DisplayMapping, TheDefaultsShowEveryLevelAsComputed) {
  EXPECT_TRUE(DisplayMapping{}.identity());
  for (int level = 0; level < 256; ++level) EXPECT_EQ(shown(level, 0.0f, 1.0f), level);
  EXPECT_FALSE((DisplayMapping{0.5f, 1.0f}.identity()));
  EXPECT_FALSE((DisplayMapping{0.0f, 2.2f}.identity()));
}

TEST(DisplayMapping, EachStopDoublesUntilWhite) {
  for (int level = 0; level < 256; ++level) {
    EXPECT_EQ(shown(level, 1.0f, 1.0f), std::min(255, 2 * level)) << level;
    EXPECT_EQ(shown(level, 2.0f, 1.0f), std::min(255, 4 * level)) << level;
  }
  // Down a stop halves, rounded to the nearest (half up): 255 -> 127.5 -> 128.
  EXPECT_EQ(shown(255, -1.0f, 1.0f), 128);
  EXPECT_EQ(shown(100, -1.0f, 1.0f), 50);
  EXPECT_EQ(shown(3, -1.0f, 1.0f), 2);
  EXPECT_EQ(shown(0, 8.0f, 1.0f), 0);  // black stays black
  // The limits: 8 stops down leaves white a level above black, 8 up makes any level above 0 white.
  EXPECT_EQ(shown(255, kMinExposureStops, 1.0f), 1);
  EXPECT_EQ(shown(1, kMaxExposureStops, 1.0f), 255);
}

TEST(DisplayMapping, GammaBendsTheMiddleAndKeepsBlackAndWhite) {
  for (const float gamma : {kMinGamma, 0.5f, 2.2f, kMaxGamma}) {
    EXPECT_EQ(shown(0, 0.0f, gamma), 0) << gamma;
    EXPECT_EQ(shown(255, 0.0f, gamma), 255) << gamma;
  }
  // 255 * (64/255)^(1/2) = 127.75; 255 * (128/255)^2 = 64.25.
  EXPECT_EQ(shown(64, 0.0f, 2.0f), 128);
  EXPECT_EQ(shown(128, 0.0f, 0.5f), 64);
  EXPECT_GT(shown(128, 0.0f, 2.2f), 128);  // above 1 brightens
  EXPECT_LT(shown(128, 0.0f, 0.8f), 128);  // below 1 darkens
}

TEST(DisplayMapping, ExposureComesBeforeGammaAndNoLevelOvertakesAnother) {
  // 32 doubled is 64, whose square root (of 64/255) is 127.75 of 255: exposure first. Gamma first would give
  // 2 * 255 * (32/255)^(1/2) = 180.6.
  EXPECT_EQ(shown(32, 1.0f, 2.0f), 128);
  for (const DisplayMapping mapping :
       {DisplayMapping{3.5f, 0.3f}, DisplayMapping{-6.0f, 4.0f}, DisplayMapping{-0.7f, 1.3f}})
    for (int level = 1; level < 256; ++level)
      EXPECT_LE(displayLevel(static_cast<std::uint8_t>(level - 1), mapping),
                displayLevel(static_cast<std::uint8_t>(level), mapping))
          << describe(mapping) << " at " << level;
}

TEST(DisplayMapping, MapsEveryChannelOfTheImageOnItsOwn) {
  Image raw(2, 1);
  const std::uint8_t values[] = {0, 10, 100, 127, 128, 255};
  std::copy(std::begin(values), std::end(values), raw.rgb.begin());
  const Image brighter = mapForDisplay(raw, DisplayMapping{1.0f, 1.0f});
  EXPECT_EQ(brighter.width, 2);
  EXPECT_EQ(brighter.height, 1);
  EXPECT_EQ(brighter.rgb, (PixelBytes{0, 20, 200, 254, 255, 255}));
  EXPECT_EQ(raw.rgb[2], 100);  // the raw image is left as it is
}

TEST(DisplayMapping, DescribesItselfForTheSavePanel) {
  EXPECT_EQ(describe(DisplayMapping{1.0f, 2.2f}), "exposure +1 stops, gamma 2.2");
  EXPECT_EQ(describe(DisplayMapping{-0.5f, 1.0f}), "exposure -0.5 stops, gamma 1");
  EXPECT_EQ(describe(DisplayMapping{}), "exposure 0 stops, gamma 1");
}

// --------------------------------------------------------------------------------------- the shown image

TEST(MappedImage, AtTheDefaultsIsTheSourceItselfAndMapsAgainOnlyOnAChange) {
  Image raw(4, 3);
  std::fill(raw.rgb.begin(), raw.rgb.end(), std::uint8_t{60});
  MappedImage shownImage;
  EXPECT_EQ(&shownImage.of(raw, 1, DisplayMapping{}), &raw);  // no copy at the defaults
  const std::uint64_t first = shownImage.serial();
  EXPECT_EQ(&shownImage.of(raw, 1, DisplayMapping{}), &raw);
  EXPECT_EQ(shownImage.serial(), first);  // nothing changed: no upload

  const DisplayMapping brighter{1.0f, 1.0f};
  const Image& mapped = shownImage.of(raw, 1, brighter);  // the mapping changed, the pass did not
  EXPECT_NE(&mapped, &raw);
  EXPECT_EQ(mapped.rgb.front(), 120);
  EXPECT_GT(shownImage.serial(), first);
  const std::uint64_t second = shownImage.serial();
  shownImage.of(raw, 1, brighter);
  EXPECT_EQ(shownImage.serial(), second);

  std::fill(raw.rgb.begin(), raw.rgb.end(), std::uint8_t{70});  // a new pass
  EXPECT_EQ(shownImage.of(raw, 2, brighter).rgb.front(), 140);
  EXPECT_GT(shownImage.serial(), second);
  const std::uint64_t third = shownImage.serial();
  EXPECT_EQ(&shownImage.of(raw, 2, DisplayMapping{}), &raw);  // reset: the pass itself again, uploaded again
  EXPECT_GT(shownImage.serial(), third);
}

TEST(NumberedFile, FramesSavedAsDisplayedGetANameOfTheirOwn) {
  const fs::path directory = freshDirectory("displayed_names");
  const std::string scene = (directory / "room.xml").string();
  const Image image(2, 2);
  EXPECT_EQ(saveFrameNumbered(image, scene).filename(), "room_001.png");
  EXPECT_EQ(saveFrameNumbered(image, scene, FrameSave::Displayed).filename(), "room_displayed_001.png");
  EXPECT_EQ(saveFrameNumbered(image, scene, FrameSave::Displayed).filename(), "room_displayed_002.png");
  EXPECT_EQ(saveFrameNumbered(image, scene, FrameSave::Raw).filename(), "room_002.png");
}

// ------------------------------------------------------------------------------------------------ scripts

std::string scriptError(const std::string& text) {
  try {
    parseScript(text, "t.rvs");
  } catch (const ScriptError& e) {
    return e.what();
  }
  return "no error";
}

TEST(AutomationScript, ExposureGammaAndDisplayedSavesParse) {
  const Script s = parseScript("set exposure +1.5\nset exposure -8\nset gamma 0.2\nset gamma 5\n"
                               "save-frame-displayed out/shown.png\nsave-frame-displayed\n",
                               "t.rvs");
  ASSERT_EQ(s.commands.size(), 6u);
  EXPECT_EQ(s.commands[0].args, std::vector<std::string>{"exposure"});
  EXPECT_EQ(s.commands[0].numbers, std::vector<double>{1.5});
  EXPECT_EQ(s.commands[1].numbers, std::vector<double>{-8.0});
  EXPECT_EQ(s.commands[2].args, std::vector<std::string>{"gamma"});
  EXPECT_EQ(s.commands[3].numbers, std::vector<double>{5.0});
  EXPECT_EQ(s.commands[4].args, std::vector<std::string>{"out/shown.png"});
  EXPECT_TRUE(s.commands[5].args.empty());  // numbered, as Ctrl+S with "Frame as displayed"
}

TEST(AutomationScript, ExposureAndGammaOutsideTheirLimitsNameTheLine) {
  EXPECT_EQ(scriptError("wait-final\nset exposure 9\n"), "t.rvs:2: 'set exposure STOPS' takes -8 to 8, not 9");
  EXPECT_EQ(scriptError("set gamma 0\n"), "t.rvs:1: 'set gamma GAMMA' takes 0.2 to 5, not 0");
  EXPECT_EQ(scriptError("set gamma 0.19\n"), "t.rvs:1: 'set gamma GAMMA' takes 0.2 to 5, not 0.19");
  EXPECT_EQ(scriptError("set exposure\n"), "t.rvs:1: usage: set exposure STOPS");
  EXPECT_EQ(scriptError("set gamma 1 2\n"), "t.rvs:1: usage: set gamma GAMMA");
  EXPECT_NE(scriptError("set exposure bright\n").find("expects a number, not 'bright'"), std::string::npos);
  EXPECT_NE(scriptError("set\n").find("exposure, gamma"), std::string::npos);
}

TEST(ScriptRunner, ExposureAndGammaNeedNoSceneAndChangeOnlyTheDisplay) {
  FakeHost host(nullptr);  // before any scene has loaded
  ScriptRunner runner(parseScript("set exposure 1\nset gamma 2.2\nset exposure -0.5\n", "t"));
  host.frame(runner);
  EXPECT_EQ(host.mapping, (DisplayMapping{1.0f, 1.0f}));
  host.frame(runner);
  EXPECT_EQ(host.mapping, (DisplayMapping{1.0f, 2.2f}));
  host.frame(runner);
  EXPECT_EQ(host.mapping, (DisplayMapping{-0.5f, 2.2f}));  // each command sets its own value, keeps the other
  EXPECT_FALSE(runner.failed()) << runner.failure();
}

TEST(ScriptRunner, SaveFrameIsRawAndSaveFrameDisplayedIsAsShownBothOfTheFinalPass) {
  SceneSession session(loadParts(), RenderSettings{});
  FakeHost host(&session);
  ScriptRunner runner(parseScript("save-frame-displayed shown.png\nsave-frame raw.png\n", "t"));
  host.frame(runner);
  host.frame(runner);
  EXPECT_EQ(host.savedFrame, "-");  // not before the final pass
  host.final = true;
  host.frame(runner);
  EXPECT_EQ(host.savedFrame, "shown.png");
  EXPECT_EQ(host.savedKind, FrameSave::Displayed);
  host.frame(runner);
  host.frame(runner);
  EXPECT_EQ(host.savedFrame, "raw.png");
  EXPECT_EQ(host.savedKind, FrameSave::Raw);
  EXPECT_FALSE(runner.failed()) << runner.failure();
}

}  // namespace
}  // namespace rayview
