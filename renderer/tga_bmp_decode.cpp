// TGA and BMP decoding (tga_bmp_decode.h): every read is checked against the bytes there are.

#include "tga_bmp_decode.h"

#include <algorithm>
#include <cstdint>
#include <cstring>

namespace rayview::detail {
namespace {

std::uint32_t le(std::string_view b, std::size_t at, int bytes) {
  std::uint32_t v = 0;
  for (int k = bytes - 1; k >= 0; --k) v = (v << 8) | static_cast<unsigned char>(b[at + static_cast<std::size_t>(k)]);
  return v;
}

bool sizeOk(long long w, long long h, long long maxPixels, std::string& reason) {
  if (w <= 0 || h <= 0) reason = "the image has no pixels";
  else if (w * h > maxPixels) reason = "the image is too large (" + std::to_string(w) + "x" + std::to_string(h) + ")";
  return reason.empty();
}

// A pixel of `bytes` bytes (BGR order, as both formats store it) to RGB; 2-byte pixels are 5-5-5.
void putPixel(const unsigned char* p, int bytes, std::uint8_t* out) {
  if (bytes == 1) {
    out[0] = out[1] = out[2] = p[0];
  } else if (bytes == 2) {
    const unsigned v = p[0] | (p[1] << 8);
    for (int c = 0; c < 3; ++c) out[2 - c] = static_cast<std::uint8_t>(((v >> (5 * c)) & 31) * 255 / 31);
  } else {
    out[0] = p[2], out[1] = p[1], out[2] = p[0];
  }
}

// The pixel at column x of a BMP row, through the palette for 1/4/8 bits, or the bit fields' masks for 32.
void bmpPixel(const unsigned char* row, int x, int bits, std::string_view palette, std::uint8_t* out) {
  if (bits >= 24) {
    putPixel(row + static_cast<std::size_t>(x) * (bits / 8), 3, out);
    return;
  }
  const int perByte = 8 / bits;
  const unsigned index = (row[x / perByte] >> (8 - bits * (x % perByte + 1))) & ((1u << bits) - 1);
  if (std::size_t{index} * 4 + 3 > palette.size()) {
    out[0] = out[1] = out[2] = 0;
    return;
  }
  putPixel(reinterpret_cast<const unsigned char*>(palette.data()) + index * 4, 3, out);
}

}  // namespace

bool looksLikeBmp(std::string_view b) { return b.size() >= 2 && b[0] == 'B' && b[1] == 'M'; }

bool looksLikeTga(std::string_view b) {
  if (b.size() < 18) return false;
  const auto type = static_cast<unsigned char>(b[2]), mapType = static_cast<unsigned char>(b[1]);
  const auto bits = static_cast<unsigned char>(b[16]);
  const bool trueColour = type == 2 || type == 10, grey = type == 3 || type == 11;
  return mapType == 0 && ((trueColour && (bits == 16 || bits == 24 || bits == 32)) || (grey && bits == 8));
}

std::optional<Texture> decodeBmp(std::string_view b, long long maxPixels, std::string& reason) {
  if (b.size() < 54) return reason = "a truncated BMP header", std::nullopt;
  const std::uint32_t offset = le(b, 10, 4), headerSize = le(b, 14, 4);
  if (headerSize < 40 || 14 + std::size_t{headerSize} > b.size()) return reason = "an unsupported BMP header", std::nullopt;
  const auto width = static_cast<std::int32_t>(le(b, 18, 4)), signedHeight = static_cast<std::int32_t>(le(b, 22, 4));
  const int bits = static_cast<int>(le(b, 28, 2));
  const std::uint32_t compression = le(b, 30, 4);
  // Bit fields (3) in a 32-bit file are almost always the plain BGRA masks, which is what is read.
  if (!(compression == 0 || (compression == 3 && bits == 32)) || !(bits == 1 || bits == 4 || bits == 8 || bits == 24 || bits == 32))
    return reason = "a compressed or " + std::to_string(bits) + "-bit BMP (rayview reads 1/4/8/24/32-bit uncompressed)", std::nullopt;
  const long long height = signedHeight < 0 ? -static_cast<long long>(signedHeight) : signedHeight;
  if (!sizeOk(width, height, maxPixels, reason)) return std::nullopt;
  const std::size_t rowBytes = ((static_cast<std::size_t>(width) * static_cast<std::size_t>(bits) + 31) / 32) * 4;
  if (offset > b.size() || rowBytes * static_cast<std::size_t>(height) > b.size() - offset)
    return reason = "a truncated BMP (fewer pixels than its header says)", std::nullopt;
  const std::string_view palette = b.substr(14 + headerSize, offset > 14 + headerSize ? offset - 14 - headerSize : 0);
  Texture t{width, static_cast<int>(height),
            PixelBytes(static_cast<std::size_t>(width) * height * 3), {}};
  for (long long y = 0; y < height; ++y) {
    const long long stored = signedHeight < 0 ? y : height - 1 - y;  // bottom-up unless the height is negative
    const auto* row = reinterpret_cast<const unsigned char*>(b.data()) + offset + rowBytes * static_cast<std::size_t>(stored);
    for (int x = 0; x < width; ++x) bmpPixel(row, x, bits, palette, &t.rgb[(static_cast<std::size_t>(y) * width + x) * 3]);
  }
  return t;
}

std::optional<Texture> decodeTga(std::string_view b, long long maxPixels, std::string& reason) {
  if (!looksLikeTga(b)) return reason = "an unsupported TGA (rayview reads true-colour and grey, plain or RLE)", std::nullopt;
  const int width = static_cast<int>(le(b, 12, 2)), height = static_cast<int>(le(b, 14, 2));
  if (!sizeOk(width, height, maxPixels, reason)) return std::nullopt;
  const int bytes = static_cast<unsigned char>(b[16]) / 8;
  const bool rle = static_cast<unsigned char>(b[2]) >= 9, topDown = (static_cast<unsigned char>(b[17]) & 0x20) != 0;
  std::size_t at = 18 + static_cast<unsigned char>(b[0]);  // after the image id
  const std::size_t pixels = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
  // The fewest bytes that can hold the pixels (RLE: a packet of 128 repeats is 1 + bytes), checked before allocating:
  // a few bytes claiming 2^28 pixels would otherwise cost 805 MB and seconds to refuse.
  const std::size_t least = rle ? (pixels + 127) / 128 * (1u + static_cast<std::size_t>(bytes))
                                : pixels * static_cast<std::size_t>(bytes);
  if (at > b.size() || b.size() - at < least) return reason = "a truncated TGA", std::nullopt;
  // A 32-bit image whose descriptor gives its pixels 8 attribute bits has alpha; any other has none.
  const bool withAlpha = bytes == 4 && (static_cast<unsigned char>(b[17]) & 0x0F) == 8;
  std::vector<std::uint8_t> stored(pixels * 3), storedAlpha(withAlpha ? pixels : 0);
  const auto* data = reinterpret_cast<const unsigned char*>(b.data());
  for (std::size_t i = 0; i < pixels;) {
    std::size_t run = 1;
    bool repeat = false;
    if (rle) {
      if (at >= b.size()) return reason = "a truncated TGA", std::nullopt;
      run = (data[at] & 0x7f) + 1u;
      repeat = (data[at++] & 0x80) != 0;
    }
    for (std::size_t k = 0; k < run && i < pixels; ++k, ++i) {
      const std::size_t from = repeat ? at : at + k * static_cast<std::size_t>(bytes);
      if (from + static_cast<std::size_t>(bytes) > b.size()) return reason = "a truncated TGA", std::nullopt;
      putPixel(data + from, bytes, &stored[i * 3]);
      if (withAlpha) storedAlpha[i] = data[from + 3];
    }
    at += (repeat ? 1 : run) * static_cast<std::size_t>(bytes);
  }
  // As for PNG: an alpha opaque everywhere is none.
  const bool opaque = !storedAlpha.empty() &&
                      std::all_of(storedAlpha.begin(), storedAlpha.end(), [](std::uint8_t a) { return a == 255; });
  if (opaque) storedAlpha = {};
  const bool alpha = !storedAlpha.empty();
  Texture t{width, height, PixelBytes(pixels * 3), std::vector<std::uint8_t>(storedAlpha.size()), opaque};
  const std::size_t rowBytes = static_cast<std::size_t>(width) * 3, w = static_cast<std::size_t>(width);
  for (int y = 0; y < height; ++y) {  // bottom-up unless the descriptor says top-down
    const auto from = static_cast<std::size_t>(topDown ? y : height - 1 - y), to = static_cast<std::size_t>(y);
    std::memcpy(&t.rgb[to * rowBytes], &stored[from * rowBytes], rowBytes);
    if (alpha) std::memcpy(&t.alpha[to * w], &storedAlpha[from * w], w);
  }
  return t;
}

}  // namespace rayview::detail
