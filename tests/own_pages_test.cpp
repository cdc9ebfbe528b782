// Big arrays on pages of their own (rayview/own_pages.h). An image's bytes (rayview/pixel_bytes.h): a big buffer is
// aligned and advised for huge pages, none of its pages is touched before a pixel is written, and the next buffer of
// the same size reuses them; filled construction still gives black; contents survive growth from the heap to pages of
// their own and back. A scene's arrays: past a huge page, a mapping no longer than asked for, its whole huge pages
// advised; under one, one whole huge page; under kOwnPagesMinBytes, the heap.
#include <cstdio>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "rayview/image.h"
#include "rayview/scene.h"

namespace rayview {
namespace {

// What /proc/self/smaps says of the mapping holding `address`.
struct Mapping {
  bool found = false;
  long sizeKb = -1;
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
    if (std::sscanf(line.c_str(), "Size: %ld kB", &value) == 1) mapping.sizeKb = value;
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
  bytes.resize(kOwnPagesMinBytes * 3);  // from the heap to pages of its own
  bytes.back() = 9;
  bytes.resize(1000);
  bytes.shrink_to_fit();  // and back
  ASSERT_EQ(bytes.size(), 1000u);
  for (int i = 0; i < 1000; ++i) ASSERT_EQ(bytes[static_cast<std::size_t>(i)], static_cast<std::uint8_t>(i * 7)) << i;
}

TEST(OwnPages, ASceneArrayMapsNoMoreThanItHoldsAndAdvisesItsWholeHugePages) {
  SceneArray<glm::dvec3> vertices;
  vertices.reserve(200000);  // 4.6 MiB: two whole huge pages and a tail
  vertices.emplace_back(1.0, 2.0, 3.0);
  const Mapping mapping = mappingOf(vertices.data());
  ASSERT_TRUE(mapping.found);
  EXPECT_EQ(reinterpret_cast<std::uintptr_t>(vertices.data()) % kHugePageBytes, 0u) << "2 MiB-aligned";
  EXPECT_LE(mapping.sizeKb * 1024, static_cast<long>(200000 * sizeof(glm::dvec3) + 4095)) << "rounded up past 4 KiB";
  if (kernelGivesHugePages() && mapping.hugePageEligible >= 0) {
    EXPECT_EQ(mapping.hugePageEligible, 1);
  }
  const SceneArray<Triangle> few(10);  // value-initialised, as any vector's
  EXPECT_EQ(few[9].vertex[2], 0u);
  const SceneArray<std::uint32_t> slots(std::size_t{1} << 20, 0);  // on pages of their own, still zeroed
  EXPECT_TRUE(std::all_of(slots.begin(), slots.end(), [](std::uint32_t v) { return v == 0; }));
}

TEST(OwnPages, AnArrayUnderAHugePageTakesAWholeOneAndASmallOneStaysOnTheHeap) {
  // Its 4 KiB pages would cost more faults than one huge page's zeroing: a BVH's nodes, a mid-sized scene's arrays.
  SceneArray<Triangle> triangles;
  triangles.reserve(kOwnPagesMinBytes / sizeof(Triangle) + 1);
  triangles.emplace_back();
  const Mapping mapping = mappingOf(triangles.data());
  ASSERT_TRUE(mapping.found);
  EXPECT_EQ(reinterpret_cast<std::uintptr_t>(triangles.data()) % kHugePageBytes, 0u) << "2 MiB-aligned";
  EXPECT_EQ(mapping.sizeKb * 1024, static_cast<long>(kHugePageBytes)) << "one whole huge page";
  if (kernelGivesHugePages() && mapping.hugePageEligible >= 0) {
    EXPECT_EQ(mapping.hugePageEligible, 1);
  }
  BigArray<std::uint32_t> small;
  small.reserve(kOwnPagesMinBytes / sizeof(std::uint32_t) / 4);
  small.push_back(7);
  EXPECT_FALSE(OwnPagesAllocator<std::uint32_t>::ownPages(small.capacity()));
  const Mapping heap = mappingOf(small.data());
  ASSERT_TRUE(heap.found);
  EXPECT_NE(heap.sizeKb * 1024, static_cast<long>(kHugePageBytes)) << "not a mapping of its own";
}

}  // namespace
}  // namespace rayview
