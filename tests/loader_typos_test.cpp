// Typos as a user meets them: a number with a letter in it names the letter and its column (O and 0 look alike in
// many fonts), a misspelled element is reported at its own line with the name it was probably meant to be, and
// resolutions of 0 or over the one image limit are refused at their element.
#include <gtest/gtest.h>

#include "support/loader_scenes.h"

namespace rayview {
namespace {

using namespace loader_testing;

TEST(LoaderTypos, ANumberWithLettersNamesEachAndItsColumn) {
  expectError(with("<maxraytracedepth>1</maxraytracedepth>", "<maxraytracedepth>1OO</maxraytracedepth>"), 2,
              "found '1OO' (letter O at column 2, letter O at column 3)");
  expectError(with("<diffuse>1 0 0</diffuse>", "<diffuse>1 0 l</diffuse>"), 22, "found 'l' (letter l at column 1)");
  expectError(with("1 3 4\n", "1 3 4O\n"), 39, "found '4O' (letter O at column 2)");
  // A Cyrillic O is not an O either.
  expectError(with("<maxraytracedepth>1</maxraytracedepth>", "<maxraytracedepth>1\xD0\x9E</maxraytracedepth>"), 2,
              "(non-ASCII byte 0xD0 at column 2, non-ASCII byte 0x9E at column 3)");
}

TEST(LoaderTypos, AMisspelledElementIsReportedAtItsLineWithDidYouMean) {
  expectError(with("<specular>1 1 1</specular>", "<specluar>1 1 1</specluar>"), 23,
              "unknown element <specluar> (did you mean <specular>?): <material id=\"red\"> has no <specular>");
  expectError(with("<materialid>red</materialid>", "<materialdi>red</materialdi>"), 36, "did you mean <materialid>?");
  expectError(with("<gaze>0 0 -1</gaze>", "<gaez>0 0 -1</gaez>"), 6, "did you mean <gaze>?");
  // An optional element misspelled is a warning at its line, with the suggestion.
  const LoadedScene loaded = load(with("<mirrorreflectance>0 0 0</mirrorreflectance>",
                                       "<mirorreflectance>0 0 0</mirorreflectance>"));
  EXPECT_TRUE(hasWarning(loaded, 25, "unknown element <mirorreflectance> ignored (did you mean <mirrorreflectance>?)"));
  // Nothing near: no suggestion, the error where it was.
  expectError(with("<specular>1 1 1</specular>", "<shininess>1 1 1</shininess>"), 20, "has no <specular>");
}

TEST(LoaderTypos, ResolutionsOfZeroOrOverTheLimitAreRefusedNotClamped) {
  expectError(with("<imageresolution>4 3</imageresolution>", "<imageresolution>0 0</imageresolution>"), 4,
              "<imageresolution> must be positive, found 0 x 0");
  expectError(with("<imageresolution>4 3</imageresolution>", "<imageresolution>1 268435456</imageresolution>"), 10,
              "1 x 268435456 pixels is too large");
}

}  // namespace
}  // namespace rayview
