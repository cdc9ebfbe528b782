#include "support/image_compare.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>

namespace rayview::testing {

std::string ImageDifference::summary() const {
  if (!sameSize) return "the images differ in size";
  char text[160];
  std::snprintf(text, sizeof text, "%.3f %% exact, %.3f %% within +-1, max channel difference %d", exactPercent,
                withinOnePercent, maxChannelDifference);
  return text;
}

ImageDifference compareImages(const Image& actual, const Image& expected) {
  ImageDifference d;
  d.sameSize = actual.width == expected.width && actual.height == expected.height;
  if (!d.sameSize || actual.width == 0 || actual.height == 0) return d;
  std::size_t exact = 0, withinOne = 0;
  const std::size_t pixels = static_cast<std::size_t>(actual.width) * actual.height;
  for (std::size_t p = 0; p < pixels; ++p) {
    int worst = 0;
    for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(int(actual.rgb[3 * p + c]) - int(expected.rgb[3 * p + c])));
    exact += worst == 0;
    withinOne += worst <= 1;
    d.maxChannelDifference = std::max(d.maxChannelDifference, worst);
  }
  d.exactPercent = 100.0 * exact / pixels;
  d.withinOnePercent = 100.0 * withinOne / pixels;
  return d;
}

std::filesystem::path testOutputDirectory() {
  std::filesystem::path dir = RAYVIEW_TEST_OUTPUT_DIR;
  std::filesystem::create_directories(dir);
  return dir;
}

std::filesystem::path writeDifferenceImages(const std::string& name, const Image& actual, const Image& expected) {
  const std::filesystem::path dir = testOutputDirectory();
  writeImageFile(dir / (name + ".actual.png"), actual);
  if (expected.width == 0) return {};
  writeImageFile(dir / (name + ".expected.png"), expected);
  if (actual.width != expected.width || actual.height != expected.height) return {};
  Image diff(actual.width, actual.height);
  for (std::size_t p = 0; p < diff.rgb.size() / 3; ++p) {
    int worst = 0;
    for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(int(actual.rgb[3 * p + c]) - int(expected.rgb[3 * p + c])));
    const std::uint8_t grey = static_cast<std::uint8_t>(expected.rgb[3 * p] / 4);
    if (worst <= 1) {
      diff.rgb[3 * p] = diff.rgb[3 * p + 1] = diff.rgb[3 * p + 2] = grey;
    } else {
      diff.rgb[3 * p] = 255;  // red: off by more than 1; brighter yellow the larger the error
      diff.rgb[3 * p + 1] = static_cast<std::uint8_t>(std::min(255, worst * 4));
      diff.rgb[3 * p + 2] = 0;
    }
  }
  const std::filesystem::path path = dir / (name + ".diff.png");
  writeImageFile(path, diff);
  return path;
}

}  // namespace rayview::testing
