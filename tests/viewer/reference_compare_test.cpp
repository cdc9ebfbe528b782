// Comparing the viewer's render with a reference image, without a window: loading (errors name the file),
// the figures of final passes, the difference image, which image shows, the keys, the `compare` script command.
#include <string>
#include <vector>

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <gtest/gtest.h>

#include "automation_script.h"
#include "navigation_input.h"
#include "rayview/grid_render.h"
#include "reference_compare.h"
#include "script_runner.h"
#include "viewer_fixtures.h"

namespace rayview {
namespace {

using namespace viewer_testing;

Image gradient(int width, int height) {
  Image image(width, height);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      for (int c = 0; c < 3; ++c) image.pixel(x, y)[c] = static_cast<std::uint8_t>((x * 31 + y * 17 + c * 50) % 256);
  return image;
}

// A final pass of `image`, as the renderer publishes it.
ProgressiveFrame finalFrame(const Image& image, std::uint64_t version) {
  ProgressiveFrame frame;
  frame.version = version;
  frame.stride = 1;
  frame.final = true;
  frame.width = image.width;
  frame.height = image.height;
  frame.image = image;
  return frame;
}

// ------------------------------------------------------------------------------------ which image shows

TEST(ImageView, SpaceShowsTheReferenceOverTheDifferenceViewOnlyWhenComparable) {
  EXPECT_EQ(chooseImageView(false, false, true), ImageView::Render);
  EXPECT_EQ(chooseImageView(true, false, true), ImageView::Reference);
  EXPECT_EQ(chooseImageView(true, true, true), ImageView::Reference);  // held: the reference, whatever the toggle
  EXPECT_EQ(chooseImageView(false, true, true), ImageView::Difference);
  // No reference of the image's size: the render, whatever is held or toggled.
  EXPECT_EQ(chooseImageView(true, false, false), ImageView::Render);
  EXPECT_EQ(chooseImageView(false, true, false), ImageView::Render);
  EXPECT_STREQ(toString(ImageView::Reference), "reference");
  EXPECT_STREQ(toString(ImageView::Difference), "difference");
  EXPECT_STREQ(toString(ImageView::Render), "render");
}

// ---------------------------------------------------------------------------------------------- loading

TEST(ReferenceComparison, LoadsPngAndPpmOfTheImagesSize) {
  const fs::path dir = freshDirectory("reference_load");
  const Image image = gradient(12, 7);
  writeImageFile(dir / "ref.png", image);
  writeImageFile(dir / "ref.ppm", image);
  ReferenceComparison comparison;
  EXPECT_FALSE(comparison.loaded());
  ASSERT_TRUE(comparison.load((dir / "ref.png").string(), 12, 7)) << comparison.loadError();
  EXPECT_EQ(comparison.reference().rgb, image.rgb);
  EXPECT_EQ(comparison.path(), (dir / "ref.png").string());
  const std::uint64_t serial = comparison.referenceSerial();
  ASSERT_TRUE(comparison.load((dir / "ref.ppm").string(), 12, 7)) << comparison.loadError();
  EXPECT_EQ(comparison.reference().rgb, image.rgb);
  EXPECT_GT(comparison.referenceSerial(), serial);  // the texture is uploaded again
  EXPECT_TRUE(comparison.loadError().empty());
}

TEST(ReferenceComparison, AWrongSizeOrUnreadableFileIsAMessageNamingItAndKeepsThePreviousReference) {
  const fs::path dir = freshDirectory("reference_errors");
  writeImageFile(dir / "good.png", gradient(12, 7));
  writeImageFile(dir / "small.ppm", gradient(6, 7));
  writeText(dir / "garbage.png", "not an image at all");
  ReferenceComparison comparison;
  ASSERT_TRUE(comparison.load((dir / "good.png").string(), 12, 7));

  EXPECT_FALSE(comparison.load((dir / "small.ppm").string(), 12, 7));
  EXPECT_NE(comparison.loadError().find("small.ppm is 6x7 but the image is 12x7"), std::string::npos)
      << comparison.loadError();
  EXPECT_FALSE(comparison.load((dir / "garbage.png").string(), 12, 7));
  EXPECT_NE(comparison.loadError().find("garbage.png"), std::string::npos) << comparison.loadError();
  EXPECT_FALSE(comparison.load((dir / "missing.png").string(), 12, 7));
  EXPECT_NE(comparison.loadError().find("missing.png"), std::string::npos) << comparison.loadError();
  EXPECT_FALSE(comparison.load(dir.string(), 12, 7));  // a directory
  EXPECT_FALSE(comparison.loadError().empty());

  // The good reference is still there.
  EXPECT_EQ(comparison.path(), (dir / "good.png").string());
  EXPECT_EQ(comparison.reference().width, 12);
  // Before a scene is on screen the size is not known: any size loads, and a frame of another size is not compared.
  ASSERT_TRUE(comparison.load((dir / "small.ppm").string(), 0, 0));
  EXPECT_NE(comparison.sizeProblem(12, 7).find("the image is 12x7 but " + (dir / "small.ppm").string() + " is 6x7"),
            std::string::npos)
      << comparison.sizeProblem(12, 7);
  EXPECT_TRUE(comparison.sizeProblem(6, 7).empty());
}

// ----------------------------------------------------------------------------------- figures, difference

TEST(ReferenceComparison, FiguresAreThoseOfTheFinalPassComparedAndForgottenWithTheReference) {
  const fs::path dir = freshDirectory("reference_figures");
  const Image reference = gradient(10, 10);
  writeImageFile(dir / "ref.png", reference);
  ReferenceComparison comparison;
  ASSERT_TRUE(comparison.load((dir / "ref.png").string(), 10, 10));
  EXPECT_FALSE(comparison.figures());

  comparison.compareFinal(reference, 5);
  ASSERT_TRUE(comparison.figures());
  EXPECT_EQ(comparison.figuresVersion(), 5u);
  EXPECT_EQ(comparison.figures()->pctExact, 100.0);

  Image edited = reference;
  edited.pixel(3, 3)[0] = static_cast<std::uint8_t>(edited.pixel(3, 3)[0] ^ 0x80);  // off by 128
  comparison.compareFinal(edited, 9);
  EXPECT_EQ(comparison.figuresVersion(), 9u);
  EXPECT_EQ(comparisonSummary(*comparison.figures()), comparisonSummary(compareToReference(edited, reference)));
  EXPECT_EQ(comparison.figures()->maxChannelDifference, 128);
  EXPECT_DOUBLE_EQ(comparison.figures()->pctExact, 99.0);

  // A frame of another size is not compared: the figures stay those of version 9.
  comparison.compareFinal(gradient(5, 10), 12);
  EXPECT_EQ(comparison.figuresVersion(), 9u);
  // Another reference: no figures until the next final pass.
  ASSERT_TRUE(comparison.load((dir / "ref.png").string(), 10, 10));
  EXPECT_FALSE(comparison.figures());
}

TEST(ReferenceComparison, TheDifferenceIsTheFalseColourMapOfTheFrameShownRecomputedPerFrameAndReference) {
  const fs::path dir = freshDirectory("reference_difference");
  const Image reference = gradient(8, 4);
  writeImageFile(dir / "ref.png", reference);
  ReferenceComparison comparison;
  ASSERT_TRUE(comparison.load((dir / "ref.png").string(), 8, 4));
  Image frame = reference;
  frame.pixel(2, 1)[1] = static_cast<std::uint8_t>(frame.pixel(2, 1)[1] ^ 0x40);
  EXPECT_EQ(comparison.difference(finalFrame(frame, 1)).rgb, differenceImage(frame, reference).rgb);
  const std::uint8_t* red = comparison.difference(finalFrame(frame, 1)).pixel(2, 1);
  EXPECT_EQ(std::vector<int>(red, red + 3), (std::vector<int>{255, 0, 0}));
  const std::uint64_t serial = comparison.differenceSerial();
  comparison.difference(finalFrame(frame, 1));
  EXPECT_EQ(comparison.differenceSerial(), serial);  // the same frame: not computed (nor uploaded) again
  EXPECT_EQ(comparison.difference(finalFrame(reference, 2)).rgb, differenceImage(reference, reference).rgb);
  EXPECT_GT(comparison.differenceSerial(), serial);
  const std::uint64_t before = comparison.differenceSerial();
  ASSERT_TRUE(comparison.load((dir / "ref.png").string(), 8, 4));
  comparison.difference(finalFrame(reference, 2));
  EXPECT_GT(comparison.differenceSerial(), before);  // another reference, the same frame version
}

TEST(ReferenceComparison, ACoarsePassIsDifferencedAsTheBlocksOnScreen) {
  const fs::path dir = freshDirectory("reference_difference_coarse");
  const Image reference = gradient(7, 3);  // blocks of 4 are cut at the right and bottom edges
  writeImageFile(dir / "ref.png", reference);
  ReferenceComparison comparison;
  ASSERT_TRUE(comparison.load((dir / "ref.png").string(), 7, 3));
  ProgressiveFrame coarse = finalFrame(gridSamples(reference, 4), 3);
  coarse.final = false;
  coarse.stride = 4;
  coarse.width = 7;
  coarse.height = 3;
  ASSERT_EQ(coarse.image.width, 2);
  const Image& difference = comparison.difference(coarse);
  ASSERT_EQ(difference.width, 7);
  ASSERT_EQ(difference.height, 3);
  EXPECT_EQ(difference.rgb, differenceImage(upscaleBlocks(coarse.image, 4, 7, 3), reference).rgb);
  // A block's sample is its top-left pixel: there the pass matches the reference; elsewhere it need not.
  const Image identical = differenceImage(reference, reference);
  auto at = [](const Image& image, int x, int y) { return std::vector<int>(image.pixel(x, y), image.pixel(x, y) + 3); };
  EXPECT_EQ(at(difference, 4, 0), at(identical, 4, 0));
  EXPECT_NE(at(difference, 5, 1), at(identical, 5, 1));
}

// ------------------------------------------------------------------------------------------------ keys

InputEvent keyEvent(int key, bool pressed, int mods = 0, bool repeat = false) {
  InputEvent e;
  e.kind = InputEvent::Kind::Key;
  e.key = key;
  e.pressed = pressed;
  e.repeat = repeat;
  e.mods = mods;
  return e;
}

TEST(CompareKeys, SpaceIsHeldAndDTogglesTheDifferenceButNotWhileTyping) {
  NavigationInput input;
  Shortcuts shortcuts;
  auto send = [&](const InputEvent& e, bool typing = false) {
    shortcuts = {};
    input.handle({e}, false, typing, 800.0, 600.0, nullptr, shortcuts);
  };
  send(keyEvent(GLFW_KEY_SPACE, true));
  EXPECT_TRUE(input.flipHeld());
  send(keyEvent(GLFW_KEY_SPACE, true, 0, true));  // the system's repeats while held
  EXPECT_TRUE(input.flipHeld());
  send(keyEvent(GLFW_KEY_SPACE, false));
  EXPECT_FALSE(input.flipHeld());

  send(keyEvent(GLFW_KEY_SPACE, true), true);  // a space typed into a field
  EXPECT_FALSE(input.flipHeld());
  send(keyEvent(GLFW_KEY_SPACE, true));
  send(keyEvent(GLFW_KEY_SPACE, false), true);  // released after a field took the focus: not stuck
  EXPECT_FALSE(input.flipHeld());
  send(keyEvent(GLFW_KEY_SPACE, true, GLFW_MOD_CONTROL));
  EXPECT_FALSE(input.flipHeld());
  send(keyEvent(GLFW_KEY_SPACE, true));
  input.releaseKeys();
  EXPECT_FALSE(input.flipHeld());

  send(keyEvent(GLFW_KEY_D, true));
  EXPECT_TRUE(shortcuts.toggleDifference);
  send(keyEvent(GLFW_KEY_D, true, 0, true));
  EXPECT_FALSE(shortcuts.toggleDifference);  // one toggle per press
  send(keyEvent(GLFW_KEY_D, true), true);
  EXPECT_FALSE(shortcuts.toggleDifference);
}

// -------------------------------------------------------------------------------------- script command

TEST(CompareScript, TakesTheRestOfTheLineAsThePath) {
  const Script s = parseScript("compare refs/my reference.png\n", "t.rvs");
  ASSERT_EQ(s.commands.size(), 1u);
  EXPECT_EQ(s.commands[0].args, std::vector<std::string>{"refs/my reference.png"});
  EXPECT_THROW(parseScript("compare\n", "t.rvs"), ScriptError);
}

TEST(CompareScript, WaitsForTheFinalPassThenPrintsTheFigures) {
  FakeHost host(nullptr);
  ScriptRunner runner(parseScript("compare ref.png\nquit 3\n", "t"));
  host.frame(runner);
  EXPECT_EQ(host.referencePath, "ref.png");
  host.frame(runner);
  EXPECT_EQ(host.exitCode, -1);  // no final pass yet
  host.comparison = compareToReference(gradient(4, 4), gradient(4, 4));
  host.final = true;
  ::testing::internal::CaptureStdout();
  host.frame(runner);
  EXPECT_EQ(::testing::internal::GetCapturedStdout(),
            "compare ref.png exact=100.000% within1=100.000% maxdiff=0 psnr=inf\n");
  EXPECT_EQ(host.exitCode, 3);
  EXPECT_FALSE(runner.failed()) << runner.failure();
}

TEST(CompareScript, AReferenceThatDoesNotLoadOrFitFailsTheScript) {
  {
    FakeHost host(nullptr);
    host.referenceError = "cannot read ref.png: no such file";
    ScriptRunner runner(parseScript("compare ref.png\n", "t"));
    host.frame(runner);
    ASSERT_TRUE(runner.failed());
    EXPECT_EQ(runner.failure(), "t:1: compare: cannot read ref.png: no such file");
  }
  {
    FakeHost host(nullptr);
    ScriptRunner runner(parseScript("wait-frames 1\ncompare ref.png\n", "t"));
    host.frame(runner);
    host.frame(runner);
    host.sizeProblem = "the image is 320x200 but ref.png is 480x300: not compared";
    host.frame(runner);
    ASSERT_TRUE(runner.failed());
    EXPECT_EQ(runner.failure(), "t:2: compare: the image is 320x200 but ref.png is 480x300: not compared");
  }
}

}  // namespace
}  // namespace rayview
