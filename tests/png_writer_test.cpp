// PNG output (renderer/png_encode.cpp): ISA-L's or zlib's deflate in parallel parts, spliced into one stream.
// Whatever the size, level and number of parts, the file must decode (libpng, through the texture decoder: an
// independent reader) to exactly the pixels written.
#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <string>
#include <utility>

#include "rayview/texture_image.h"

#include "rayview/image.h"
#include "support/image_compare.h"

namespace rayview {
namespace {

// Flat regions, gradients and noise: long matches, short matches and literals all occur.
Image testImage(int width, int height, std::uint32_t seed) {
  Image image(width, height);
  std::mt19937 random(seed);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      std::uint8_t* p = image.pixel(x, y);
      if (x < width / 3) {
        p[0] = 20, p[1] = 20, p[2] = 40;
      } else if (x < 2 * width / 3) {
        p[0] = static_cast<std::uint8_t>(x + y), p[1] = static_cast<std::uint8_t>(2 * y), p[2] = static_cast<std::uint8_t>(x);
      } else {
        const std::uint32_t r = random();
        p[0] = static_cast<std::uint8_t>(r), p[1] = static_cast<std::uint8_t>(r >> 8), p[2] = static_cast<std::uint8_t>(r >> 16);
      }
    }
  return image;
}

// Decoded by libpng (rayview's image reader): another implementation than the writer's.
void expectDecodesTo(const std::string& png, const Image& image) {
  std::string reason;
  const std::optional<Texture> decoded = detail::decodeImage(png, reason);
  ASSERT_TRUE(decoded.has_value()) << reason;
  EXPECT_EQ(decoded->width, image.width);
  EXPECT_EQ(decoded->height, image.height);
  if (decoded->width == image.width && decoded->height == image.height) {
    EXPECT_TRUE(decoded->rgb == image.rgb) << "pixels differ";
  }
}

TEST(PngWriter, RoundTripsAtEveryLevelAndPartCount) {
  // 1024x768 is large enough for several 256 KiB parts; the small sizes fit in one.
  for (auto [w, h] : {std::pair{1, 1}, std::pair{7, 3}, std::pair{333, 211}, std::pair{1024, 768}})
    for (int level : {1, 6, 9})
      for (int threads : {1, 2, 3, 8}) {
        SCOPED_TRACE(std::to_string(w) + "x" + std::to_string(h) + " level " + std::to_string(level) + " threads " +
                     std::to_string(threads));
        const Image image = testImage(w, h, static_cast<std::uint32_t>(w * 31 + level));
        expectDecodesTo(encodePng(image, PngOptions{level, threads}), image);
      }
}

// Noise does not compress: every part's output outgrows the room it starts with (an eighth of the part) and is
// grown until it holds more than the part itself.
TEST(PngWriter, IncompressibleImagesRoundTrip) {
  for (auto [w, h] : {std::pair{64, 64}, std::pair{1024, 768}})
    for (int level : {1, 9})
      for (int threads : {1, 2, 8}) {
        SCOPED_TRACE(std::to_string(w) + "x" + std::to_string(h) + " level " + std::to_string(level) + " threads " +
                     std::to_string(threads));
        Image image(w, h);
        std::mt19937 random(static_cast<std::uint32_t>(w + level + threads));
        for (std::uint8_t& byte : image.rgb) byte = static_cast<std::uint8_t>(random() >> 24);
        const std::string png = encodePng(image, PngOptions{level, threads});
        EXPECT_GT(png.size(), image.rgb.size());
        expectDecodesTo(png, image);
      }
}

TEST(PngWriter, SameBytesForTheSameOptions) {
  const Image image = testImage(800, 600, 5);
  EXPECT_EQ(encodePng(image, PngOptions{1, 2}), encodePng(image, PngOptions{1, 2}));
}

// The overload that takes the image (what `rayview render` uses, so that the write does not hold the pixels): the
// same file as from a borrowed image.
TEST(PngWriter, AnImageGivenAwayWritesTheSameFile) {
  const std::filesystem::path dir = testing::testOutputDirectory() / "png_writer";
  std::filesystem::create_directories(dir);
  const Image image = testImage(333, 211, 12);
  for (const char* name : {"given.png", "given.ppm"}) {
    Image given = image;
    writeImageFile(dir / name, std::move(given));
    EXPECT_EQ(readImageFile(dir / name).rgb, image.rgb) << name;
  }
}

// A file is written as the pieces it was made in (the PNG's headers, each deflated part, its trailer; the PPM's header
// and the pixels where they are), never gathered: the file must hold exactly those bytes, in order.
TEST(PngWriter, TheFileHoldsExactlyTheEncodedBytes) {
  const std::filesystem::path dir = testing::testOutputDirectory() / "png_writer";
  std::filesystem::create_directories(dir);
  const Image image = testImage(1024, 768, 21);  // several parts
  const auto fileBytes = [](const std::filesystem::path& file) {
    std::ifstream in(file, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
  };
  const FileBytes pieces = encodePngFile(image);
  EXPECT_GT(pieces.pieces.size(), 3u) << "headers, two parts or more, trailer";
  EXPECT_EQ(pieces.joined(), encodePng(image));
  writeImageFile(dir / "pieces.png", image);
  EXPECT_EQ(fileBytes(dir / "pieces.png"), encodePng(image));
  Image given = image;
  writeImageFile(dir / "pieces_given.png", std::move(given));
  EXPECT_EQ(fileBytes(dir / "pieces_given.png"), encodePng(image));

  const std::string ppm = "P6\n1024 768\n255\n" + std::string(image.rgb.begin(), image.rgb.end());
  writeImageFile(dir / "pieces.ppm", image);
  EXPECT_EQ(fileBytes(dir / "pieces.ppm"), ppm);
  given = image;
  writeImageFile(dir / "pieces_given.ppm", std::move(given));
  EXPECT_EQ(fileBytes(dir / "pieces_given.ppm"), ppm);
}

TEST(PngWriter, WrittenFileReadsBack) {
  const Image image = testImage(640, 480, 9);
  const std::filesystem::path dir = testing::testOutputDirectory() / "png_writer";
  std::filesystem::create_directories(dir);
  const std::filesystem::path file = dir / "round_trip.png";
  writeImageFile(file, image);
  const Image back = readImageFile(file);
  ASSERT_EQ(back.width, image.width);
  ASSERT_EQ(back.height, image.height);
  EXPECT_EQ(back.rgb, image.rgb);
}

}  // namespace
}  // namespace rayview
