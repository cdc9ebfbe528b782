// The bytes of an image (rayview/pixel_bytes.h): a big buffer has pages of its own, aligned and advised for huge
// pages, and none of them is touched before a pixel is written; the next buffer of the same size reuses them; filled
// construction still gives black; contents survive growth from the heap to pages of their own and back.
#include <cstdio>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "rayview/image.h"

namespace rayview {
namespace {

// What /proc/self/smaps says of the mapping holding `address`.
struct Mapping {
  bool found = false;
  long residentKb = -1;
  int hugePageEligible = -1;  // THPeligible
};

Mapping mappingOf(const void* address) {
  const auto at = reinterpret_cast<std::uintptr_t>(address);
  std::ifstream smaps("/proc/self/smaps");
  Mapping mapping;
  bool inside = false;
  for (std::string line; std::getline(smaps, line);) {
    unsigned long low = 0, high = 0;
    char dash = 0;
    if (std::sscanf(line.c_str(), "%lx%c%lx ", &low, &dash, &high) == 3 && dash == '-') {
      if (mapping.found) break;
      inside = at >= low && at < high;
      mapping.found = inside;
      continue;
    }
    if (!inside) continue;
    long value = 0;
    if (std::sscanf(line.c_str(), "Rss: %ld kB", &value) == 1) mapping.residentKb = value;
    if (std::sscanf(line.c_str(), "THPeligible: %ld", &value) == 1) mapping.hugePageEligible = static_cast<int>(value);
  }
  return mapping;
}

bool kernelGivesHugePages() {
  std::ifstream enabled("/sys/kernel/mm/transparent_hugepage/enabled");
  std::string modes;
  std::getline(enabled, modes);
  return !modes.empty() && modes.find("[never]") == std::string::npos;
}

TEST(PixelBytes, ABigFrameIsNotTouchedBeforeItsPixelsAreWritten) {
  const Image frame = Image::unfilled(1920, 1080);  // 6 MiB
  ASSERT_EQ(frame.rgb.size(), std::size_t{1920} * 1080 * 3);
  EXPECT_EQ(reinterpret_cast<std::uintptr_t>(frame.rgb.data()) % (std::size_t{1} << 21), 0u) << "2 MiB-aligned";
  const Mapping mapping = mappingOf(frame.rgb.data());
  ASSERT_TRUE(mapping.found);
  EXPECT_EQ(mapping.residentKb, 0) << "a byte of the frame was written before the render";
  if (kernelGivesHugePages() && mapping.hugePageEligible >= 0) {
    EXPECT_EQ(mapping.hugePageEligible, 1) << "the frame's pages are not advised for huge pages";
  }
}

TEST(PixelBytes, WrittenPagesBecomeResident) {
  Image frame = Image::unfilled(1024, 1024);
  *frame.pixel(512, 512) = 7;
  EXPECT_GT(mappingOf(frame.rgb.data()).residentKb, 0) << "the smaps reading above would pass for anything";
  EXPECT_EQ(*frame.pixel(512, 512), 7);
}

TEST(PixelBytes, AnImageMadeWithASizeIsBlack) {
  for (const int side : {16, 1024}) {  // from the heap, and on pages of its own
    Image image = Image::unfilled(side, side);
    std::fill(image.rgb.begin(), image.rgb.end(), std::uint8_t{200});
    image = Image();
    const Image black(side, side);
    EXPECT_TRUE(std::all_of(black.rgb.begin(), black.rgb.end(), [](std::uint8_t b) { return b == 0; })) << side;
  }
}

TEST(PixelBytes, AFrameOfTheSameSizeAgainReusesThePagesOfTheLast) {
  Image first = Image::unfilled(1000, 1000);
  std::fill(first.rgb.begin(), first.rgb.end(), std::uint8_t{1});
  const std::uint8_t* const pages = first.rgb.data();
  first = Image();
  const Image again = Image::unfilled(1000, 1000);  // a viewer's next copy of a pass: no fresh pages to fault in
  EXPECT_EQ(again.rgb.data(), pages);
  const Image other = Image::unfilled(2000, 1000);
  EXPECT_NE(other.rgb.data(), pages);
}

TEST(PixelBytes, ContentsSurviveGrowthAndShrinking) {
  PixelBytes bytes;
  for (int i = 0; i < 1000; ++i) bytes.push_back(static_cast<std::uint8_t>(i * 7));
  bytes.resize(kOwnPagesBytes * 3);  // from the heap to pages of its own
  bytes.back() = 9;
  bytes.resize(1000);
  bytes.shrink_to_fit();  // and back
  ASSERT_EQ(bytes.size(), 1000u);
  for (int i = 0; i < 1000; ++i) ASSERT_EQ(bytes[static_cast<std::size_t>(i)], static_cast<std::uint8_t>(i * 7)) << i;
}

}  // namespace
}  // namespace rayview
