// PNG decoding with libpng's simplified API (Debian's libpng-dev): fuzzing found Debian 12's stb_image
// passing null pointers to memcpy on malformed PNGs (undefined behaviour; tests/fuzz_regressions/texture/),
// after its JPEG, PNM and GIF decoders had failed the same way. libpng is the PNG decoder the rest of the
// system trusts and that is fuzzed continuously upstream.
#include "png_decode.h"

#include <png.h>

namespace rayview::detail {

bool looksLikePng(std::string_view bytes) {
  return bytes.size() >= 8 && png_sig_cmp(reinterpret_cast<png_const_bytep>(bytes.data()), 0, 8) == 0;
}

namespace {

// Whether every chunk's declared length fits in the bytes that follow it. libpng allocates a chunk's declared
// length before reading its data, so a 100-byte file declaring a 2 GB text chunk made it allocate 2 GB (fuzzing,
// libFuzzer's out-of-memory); the file in memory says how long a chunk can be.
bool chunkLengthsFit(std::string_view bytes) {
  std::size_t at = 8;
  while (at + 8 <= bytes.size()) {
    const auto* p = reinterpret_cast<const unsigned char*>(bytes.data() + at);
    const std::size_t length = (std::size_t{p[0]} << 24) | (std::size_t{p[1]} << 16) | (std::size_t{p[2]} << 8) | p[3];
    if (length > bytes.size() - at - 8) return false;
    if (bytes.substr(at + 4, 4) == "IEND") return true;  // what follows the image is not libpng's to read
    at += 8 + length + 4;  // length, type, data, CRC
  }
  return true;
}

}  // namespace

std::optional<Texture> decodePng(std::string_view bytes, long long maxPixels, std::string& reason) {
  if (!chunkLengthsFit(bytes)) {
    reason = "cannot be decoded (a chunk is longer than the file)";
    return std::nullopt;
  }
  png_image image{};
  image.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_memory(&image, bytes.data(), bytes.size())) {
    reason = std::string("cannot be decoded (") + image.message + ")";
    png_image_free(&image);
    return std::nullopt;
  }
  if (image.width == 0 || image.height == 0 || static_cast<long long>(image.width) * image.height > maxPixels) {
    reason = "image too large (" + std::to_string(image.width) + " x " + std::to_string(image.height) + ")";
    png_image_free(&image);
    return std::nullopt;
  }
  // RGBA, 8 bits: the colour as stored (no compositing over a background), the alpha dropped below.
  image.format = PNG_FORMAT_RGBA;
  std::vector<unsigned char> rgba(PNG_IMAGE_SIZE(image));
  if (!png_image_finish_read(&image, nullptr, rgba.data(), 0, nullptr)) {
    reason = std::string("cannot be decoded (") + image.message + ")";
    png_image_free(&image);
    return std::nullopt;
  }
  Texture texture;
  texture.width = static_cast<int>(image.width);
  texture.height = static_cast<int>(image.height);
  const std::size_t pixels = static_cast<std::size_t>(image.width) * image.height;
  texture.rgb.resize(pixels * 3);
  for (std::size_t p = 0; p < pixels; ++p)
    for (int c = 0; c < 3; ++c) texture.rgb[p * 3 + c] = rgba[p * 4 + c];
  return texture;
}

}  // namespace rayview::detail
