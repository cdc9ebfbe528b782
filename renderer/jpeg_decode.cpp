// JPEG decoding with libjpeg-turbo (Debian's libjpeg62-turbo-dev): stb_image's JPEG decoder in Debian 12
// writes out of bounds on a malformed Huffman table (found by fuzzing the texture reader; the reproducer is
// in tests/fuzz_regressions/texture/). libjpeg-turbo is the decoder the rest of the system trusts and fuzzes.
#include "jpeg_decode.h"

#include <csetjmp>
#include <cstdio>

#include <jpeglib.h>

#include "rayview/image_limits.h"

namespace rayview::detail {
namespace {

struct ErrorManager {
  jpeg_error_mgr base;  // first: libjpeg hands back a pointer to it
  std::jmp_buf jump;
  char message[JMSG_LENGTH_MAX] = {};
};

[[noreturn]] void onError(j_common_ptr info) {
  auto* errors = reinterpret_cast<ErrorManager*>(info->err);
  info->err->format_message(info, errors->message);
  std::longjmp(errors->jump, 1);
}

// A warning (level -1) is corrupt or missing data the decoder would paper over (a truncated file reads as grey
// rows): the file is refused, as an error is. Trace messages (levels 0 and up) stay quiet.
void onMessage(j_common_ptr info, int level) {
  if (level < 0) onError(info);
}

}  // namespace

bool looksLikeJpeg(std::string_view bytes) {
  return bytes.size() >= 3 && static_cast<unsigned char>(bytes[0]) == 0xFF &&
         static_cast<unsigned char>(bytes[1]) == 0xD8 && static_cast<unsigned char>(bytes[2]) == 0xFF;
}

namespace {

// Between setjmp and a longjmp back to it, no automatic object with a destructor is alive and nothing local
// is changed that is read after the jump: the pixels go into `out`, owned by the caller, and libjpeg's memory
// is released by jpeg_destroy_decompress.
bool decodeInto(std::string_view bytes, long long maxPixels, Texture& out, std::string& reason) {
  jpeg_decompress_struct info{};
  ErrorManager errors;
  info.err = jpeg_std_error(&errors.base);
  errors.base.error_exit = onError;
  errors.base.emit_message = onMessage;
  if (setjmp(errors.jump)) {
    jpeg_destroy_decompress(&info);
    reason = std::string("cannot be decoded (") + errors.message + ")";
    return false;
  }
  jpeg_create_decompress(&info);
  jpeg_mem_src(&info, reinterpret_cast<const unsigned char*>(bytes.data()), static_cast<unsigned long>(bytes.size()));
  jpeg_read_header(&info, TRUE);
  if (!imageSizeProblem(info.image_width, info.image_height).empty() ||
      static_cast<long long>(info.image_width) * info.image_height > maxPixels) {
    jpeg_destroy_decompress(&info);
    reason = imageSizeProblem(info.image_width, info.image_height);
    return false;
  }
  info.out_color_space = JCS_RGB;
  jpeg_start_decompress(&info);
  out.width = static_cast<int>(info.output_width);
  out.height = static_cast<int>(info.output_height);
  try {
    out.rgb.resize(static_cast<std::size_t>(out.width) * out.height * 3);
  } catch (...) {  // the pixels' allocation (std::bad_alloc): libjpeg's memory is released, the caller told
    jpeg_destroy_decompress(&info);
    throw;
  }
  while (info.output_scanline < info.output_height) {
    unsigned char* row = out.rgb.data() + static_cast<std::size_t>(info.output_scanline) * out.width * 3;
    jpeg_read_scanlines(&info, &row, 1);
  }
  jpeg_finish_decompress(&info);
  jpeg_destroy_decompress(&info);
  return true;
}

}  // namespace

std::optional<Texture> decodeJpeg(std::string_view bytes, long long maxPixels, std::string& reason) {
  Texture texture;
  if (!decodeInto(bytes, maxPixels, texture, reason)) return std::nullopt;
  return texture;
}

}  // namespace rayview::detail
