#include "stb_native_png.h"

#include <cstdlib>

#define STB_IMAGE_WRITE_STATIC
#define STB_IMAGE_WRITE_IMPLEMENTATION
#define STBI_WRITE_NO_STDIO
#include <stb_image_write.h>

namespace rayview::bench {

std::string stbNativePng(const Image& image, int level, int filter) {
  // Single-threaded use only: stb's settings are globals.
  stbi_write_png_compression_level = level;
  stbi_write_force_png_filter = filter;
  int length = 0;
  unsigned char* png = stbi_write_png_to_mem(image.rgb.data(), image.width * 3, image.width, image.height, 3, &length);
  std::string bytes(reinterpret_cast<const char*>(png), static_cast<std::size_t>(length));
  std::free(png);
  return bytes;
}

int stbNativeDeflate(const unsigned char* data, int bytes, int level) {
  int length = 0;
  unsigned char* z = stbi_zlib_compress(const_cast<unsigned char*>(data), bytes, &length, level);
  std::free(z);
  return length;
}

}  // namespace rayview::bench
