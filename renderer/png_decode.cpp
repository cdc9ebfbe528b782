// PNG decoding with libpng (Debian's libpng-dev): fuzzing found Debian 12's stb_image passing null pointers to
// memcpy on malformed PNGs (undefined behaviour; tests/fuzz_regressions/texture/), after its JPEG, PNM and GIF
// decoders had failed the same way. libpng is the PNG decoder the rest of the system trusts and that is fuzzed
// continuously upstream. Its full interface, not the simplified one: that one treats a 16-bit file without colour
// chunks as linear light and gamma-encodes it, where rayview wants the values the file holds.
#include "png_decode.h"

#include <png.h>

#include <csetjmp>
#include <cstring>

#include "rayview/image_limits.h"

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

struct Reading {
  std::string_view bytes;
  std::size_t at = 0;
  std::jmp_buf jump;
  char message[256] = {};
};

void readBytes(png_structp png, png_bytep into, png_size_t count) {
  auto* reading = static_cast<Reading*>(png_get_io_ptr(png));
  if (count > reading->bytes.size() - reading->at) png_error(png, "the file ends before the image does");
  std::memcpy(into, reading->bytes.data() + reading->at, count);
  reading->at += count;
}

[[noreturn]] void onError(png_structp png, png_const_charp message) {
  auto* reading = static_cast<Reading*>(png_get_error_ptr(png));
  std::strncpy(reading->message, message, sizeof reading->message - 1);
  std::longjmp(reading->jump, 1);
}

void onWarning(png_structp, png_const_charp) {}  // ancillary-chunk problems: the samples are still exact

// 8-bit RGB as stored: palettes and low bit depths expanded, 16-bit samples scaled (v * 255 / 65535, rounded),
// grey made RGB, no gamma or colour-space conversion; an alpha channel or tRNS chunk read as a fourth sample (8-bit,
// scaled alike), which decodeInto moves to Texture::alpha (the colour is never composited with it).
// Returns the samples a pixel: 3 or 4.
unsigned setTransforms(png_structp png, png_infop info) {
  png_set_expand(png);
  png_set_scale_16(png);
  const int colour = png_get_color_type(png, info);
  if (colour == PNG_COLOR_TYPE_GRAY || colour == PNG_COLOR_TYPE_GRAY_ALPHA) png_set_gray_to_rgb(png);
  png_set_interlace_handling(png);
  png_read_update_info(png, info);
  return png_get_channels(png, info);
}

// RGBA pixels (4 a pixel, in `out.rgb`) to RGB in place plus their alpha apart: each pixel's colour moves down to
// its RGB place, which never overtakes what is still to be read. An alpha that is opaque everywhere (many models'
// RGBA textures) is dropped: such an image is as one without, and costs no more.
void splitAlpha(Texture& out, std::size_t pixels) {
  out.alpha.resize(pixels);
  std::uint8_t* samples = out.rgb.data();
  bool opaque = true;
  for (std::size_t i = 0; i < pixels; ++i) {
    out.alpha[i] = samples[i * 4 + 3];
    opaque &= out.alpha[i] == 255;
    std::memmove(samples + i * 3, samples + i * 4, 3);
  }
  if (opaque) {
    out.alpha = {};
    out.opaqueAlpha = true;
  }
  out.rgb.resize(pixels * 3);
  out.rgb.shrink_to_fit();
}

// Between setjmp and a longjmp back to it, no automatic object with a destructor is alive and nothing local is
// changed that is read after the jump: the pixels and rows belong to the caller.
bool decodeInto(Reading& reading, png_structp png, png_infop info, Texture& out, std::vector<png_bytep>& rows,
                std::string& reason) {
  if (setjmp(reading.jump)) {
    reason = std::string("cannot be decoded (") + reading.message + ")";
    return false;
  }
  png_set_read_fn(png, &reading, readBytes);
  png_read_info(png, info);
  const png_uint_32 width = png_get_image_width(png, info), height = png_get_image_height(png, info);
  if (std::string problem = imageSizeProblem(width, height); !problem.empty()) {
    reason = problem;
    return false;
  }
  const unsigned channels = setTransforms(png, info);
  if ((channels != 3 && channels != 4) || png_get_rowbytes(png, info) != static_cast<std::size_t>(width) * channels)
    png_error(png, "unexpected row layout");
  out.width = static_cast<int>(width);
  out.height = static_cast<int>(height);
  const std::size_t pixels = static_cast<std::size_t>(width) * height;
  out.rgb.resize(pixels * channels);
  rows.resize(height);
  for (png_uint_32 y = 0; y < height; ++y) rows[y] = out.rgb.data() + static_cast<std::size_t>(y) * width * channels;
  png_read_image(png, rows.data());
  png_read_end(png, nullptr);
  if (channels == 4) splitAlpha(out, pixels);
  return true;
}

}  // namespace

std::optional<Texture> decodePng(std::string_view bytes, long long maxPixels, std::string& reason) {
  static_cast<void>(maxPixels);  // the one image limit (rayview/image_limits.h) applies
  if (!chunkLengthsFit(bytes)) {
    reason = "cannot be decoded (a chunk is longer than the file)";
    return std::nullopt;
  }
  Reading reading;
  reading.bytes = bytes;
  png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &reading, onError, onWarning);
  if (!png) {
    reason = "cannot be decoded (libpng could not start)";
    return std::nullopt;
  }
  png_infop info = png_create_info_struct(png);
  // libpng refuses a larger side itself, before its own row buffers are allocated.
  png_set_user_limits(png, static_cast<png_uint_32>(kMaxImageSide), static_cast<png_uint_32>(kMaxImageSide));
  Texture texture;
  std::vector<png_bytep> rows;
  bool ok = false;
  try {
    ok = info && decodeInto(reading, png, info, texture, rows, reason);
  } catch (...) {  // the pixels' allocation (std::bad_alloc): libpng's memory is released, the caller told
    png_destroy_read_struct(&png, info ? &info : nullptr, nullptr);
    throw;
  }
  if (!info) reason = "cannot be decoded (libpng could not start)";
  png_destroy_read_struct(&png, info ? &info : nullptr, nullptr);
  if (!ok) return std::nullopt;
  return texture;
}

}  // namespace rayview::detail
