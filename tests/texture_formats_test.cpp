// TGA and BMP textures (renderer/tga_bmp_decode.h, through decodeImage as every texture is read), on images the
// test writes: each variant's pixels where they belong, truncated files refused. PNG's alpha kept apart from the
// colour (for cut-outs), the colour exactly as without it.
#include <gtest/gtest.h>

#include <cstdint>
#include <string>

#include "rayview/image.h"
#include "rayview/texture_image.h"
#include "support/rgba_png.h"

namespace rayview {
namespace {

void put(std::string& s, std::uint32_t v, int bytes) {
  for (int k = 0; k < bytes; ++k) s.push_back(static_cast<char>((v >> (8 * k)) & 0xff));
}

// A 2x2 image: top row red, green; bottom row blue, white.
const std::uint8_t kTop[2][3] = {{255, 0, 0}, {0, 255, 0}}, kBottom[2][3] = {{0, 0, 255}, {255, 255, 255}};

void expectPixels(const std::string& bytes, const char* what) {
  std::string reason;
  const std::optional<Texture> t = detail::decodeImage(bytes, reason);
  ASSERT_TRUE(t) << what << ": " << reason;
  ASSERT_EQ(t->width, 2);
  ASSERT_EQ(t->height, 2);
  for (int x = 0; x < 2; ++x)
    for (int c = 0; c < 3; ++c) {
      EXPECT_EQ(t->rgb[static_cast<std::size_t>(x * 3 + c)], kTop[x][c]) << what << " top " << x;
      EXPECT_EQ(t->rgb[static_cast<std::size_t>(6 + x * 3 + c)], kBottom[x][c]) << what << " bottom " << x;
    }
}

std::string tgaHeader(int type, int bits) {
  std::string s(18, '\0');
  s[2] = static_cast<char>(type);
  s[12] = 2, s[14] = 2, s[16] = static_cast<char>(bits);
  return s;
}

void bgr(std::string& s, const std::uint8_t* p) { s += {static_cast<char>(p[2]), static_cast<char>(p[1]), static_cast<char>(p[0])}; }

TEST(TextureFormats, ReadsPlainAndRunLengthTga) {
  std::string plain = tgaHeader(2, 24);  // bottom row first
  for (const auto* row : {kBottom, kTop})
    for (int x = 0; x < 2; ++x) bgr(plain, row[x]);
  expectPixels(plain, "plain TGA");
  std::string rle = tgaHeader(10, 24);
  rle.push_back(static_cast<char>(0x01));  // a raw packet of 2: blue, white
  bgr(rle, kBottom[0]);
  bgr(rle, kBottom[1]);
  rle.push_back(static_cast<char>(0x80));  // a run of 1: red
  bgr(rle, kTop[0]);
  rle.push_back(static_cast<char>(0x00));  // a raw packet of 1: green
  bgr(rle, kTop[1]);
  expectPixels(rle, "RLE TGA");
  std::string reason;
  EXPECT_FALSE(detail::decodeImage(plain.substr(0, plain.size() - 2), reason));
  EXPECT_NE(reason.find("truncated"), std::string::npos) << reason;
}

// A 32-bit TGA with 8 attribute bits keeps them as alpha (its colour as without); a 24-bit one has none.
TEST(TextureFormats, ThirtyTwoBitTgaKeepsItsAlpha) {
  std::string tga = tgaHeader(2, 32);
  tga[17] = 8;  // 8 attribute bits, bottom row first
  std::uint8_t a = 10;
  for (const auto* row : {kBottom, kTop})
    for (int x = 0; x < 2; ++x) bgr(tga, row[x]), tga.push_back(static_cast<char>(a)), a = static_cast<std::uint8_t>(a + 60);
  expectPixels(tga, "32-bit TGA");
  std::string reason;
  const std::optional<Texture> t = detail::decodeImage(tga, reason);
  ASSERT_TRUE(t) << reason;
  EXPECT_EQ(t->alpha, (std::vector<std::uint8_t>{130, 190, 10, 70}));  // top row first
  std::string plain = tgaHeader(2, 24);
  for (const auto* row : {kBottom, kTop})
    for (int x = 0; x < 2; ++x) bgr(plain, row[x]);
  EXPECT_TRUE(detail::decodeImage(plain, reason)->alpha.empty());
}

// A few bytes whose header claims 16384 x 16384 pixels (a fuzzer's find, minimized): refused as truncated, from the
// sizes alone, for plain and run-length data alike.
TEST(TextureFormats, ATgaFarShorterThanItsHeaderSaysIsTruncated) {
  for (int type : {2, 10}) {
    std::string huge = tgaHeader(type, 24);
    huge[12] = 0, huge[13] = 0x40, huge[14] = 0, huge[15] = 0x40;
    huge += std::string(9, '\x80');
    std::string reason;
    EXPECT_FALSE(detail::decodeImage(huge, reason)) << type;
    EXPECT_NE(reason.find("a truncated TGA"), std::string::npos) << type << ": " << reason;
  }
}

TEST(TextureFormats, ReadsTwentyFourBitAndPalettedBmp) {
  auto bmp = [](int bits, const std::string& palette, const std::string& pixels) {
    std::string s = "BM";
    put(s, static_cast<std::uint32_t>(54 + palette.size() + pixels.size()), 4);
    put(s, 0, 4);
    put(s, static_cast<std::uint32_t>(54 + palette.size()), 4);
    put(s, 40, 4), put(s, 2, 4), put(s, 2, 4), put(s, 1, 2), put(s, static_cast<std::uint32_t>(bits), 2);
    for (int k = 0; k < 6; ++k) put(s, 0, 4);
    return s + palette + pixels;
  };
  std::string rows;  // bottom-up, each row padded to 4 bytes
  for (const auto* row : {kBottom, kTop}) {
    for (int x = 0; x < 2; ++x) bgr(rows, row[x]);
    rows += std::string(2, '\0');
  }
  expectPixels(bmp(24, "", rows), "24-bit BMP");
  std::string palette;
  for (const auto* p : {kTop[0], kTop[1], kBottom[0], kBottom[1]}) bgr(palette, p), palette.push_back('\0');
  expectPixels(bmp(8, palette, std::string("\2\3\0\0\0\1\0\0", 8)), "8-bit BMP");
  std::string reason;
  EXPECT_FALSE(detail::decodeImage(bmp(24, "", rows).substr(0, 60), reason));
  EXPECT_NE(reason.find("truncated"), std::string::npos) << reason;
}

// An RGBA PNG decodes to the same colour as the RGB PNG of its colour, with its alpha kept beside; grey and alpha
// decodes to grey RGB and the alpha; a PNG without alpha carries none.
TEST(TextureFormats, PngKeepsItsAlphaApartAndItsColourAsItIs) {
  std::vector<std::uint8_t> rgba;
  Image colour(3, 2);
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 3; ++x) {
      const std::uint8_t r = std::uint8_t(40 * x + 7), g = std::uint8_t(90 * y + 3), b = std::uint8_t(200 - 30 * x);
      rgba.insert(rgba.end(), {r, g, b, std::uint8_t(x * 100 + y)});
      colour.pixel(x, y)[0] = r, colour.pixel(x, y)[1] = g, colour.pixel(x, y)[2] = b;
    }
  std::string reason;
  const std::optional<Texture> withAlpha = detail::decodeImage(testing::encodePngWithAlpha(3, 2, 4, rgba), reason);
  const std::optional<Texture> without = detail::decodeImage(encodePng(colour), reason);
  ASSERT_TRUE(withAlpha && without) << reason;
  EXPECT_EQ(withAlpha->rgb, without->rgb);
  EXPECT_EQ(withAlpha->rgb, colour.rgb);
  EXPECT_EQ(withAlpha->alpha, (std::vector<std::uint8_t>{0, 100, 200, 1, 101, 201}));
  EXPECT_TRUE(without->alpha.empty());
  EXPECT_EQ(detail::decodeImage(encodeTexturePng(*withAlpha), reason), withAlpha);  // written back with its alpha

  const std::optional<Texture> grey =
      detail::decodeImage(testing::encodePngWithAlpha(2, 1, 2, {10, 0, 250, 255}), reason);
  ASSERT_TRUE(grey) << reason;
  EXPECT_EQ(grey->rgb, (PixelBytes{10, 10, 10, 250, 250, 250}));
  EXPECT_EQ(grey->alpha, (std::vector<std::uint8_t>{0, 255}));
  // Opaque everywhere: no alpha to carry.
  const std::optional<Texture> opaque =
      detail::decodeImage(testing::encodePngWithAlpha(2, 1, 2, {10, 255, 250, 255}), reason);
  ASSERT_TRUE(opaque) << reason;
  EXPECT_TRUE(opaque->alpha.empty());
  EXPECT_TRUE(opaque->opaqueAlpha);
  EXPECT_FALSE(without->opaqueAlpha);
}

}  // namespace
}  // namespace rayview
