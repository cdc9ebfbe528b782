#include "support/rgba_png.h"

#include <stdexcept>

#define STB_IMAGE_WRITE_STATIC
#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb_image_write.h>

namespace rayview::testing {

std::string encodePngWithAlpha(int width, int height, int channels, const std::vector<std::uint8_t>& samples) {
  std::string bytes;
  const auto append = [](void* context, void* data, int size) {
    static_cast<std::string*>(context)->append(static_cast<const char*>(data), static_cast<std::size_t>(size));
  };
  if (!stbi_write_png_to_func(append, &bytes, width, height, channels, samples.data(), width * channels))
    throw std::runtime_error("stb_image_write could not encode the test's PNG");
  return bytes;
}

std::vector<std::uint8_t> leftHalfClear(int width, int height, std::uint8_t r, std::uint8_t g, std::uint8_t b) {
  std::vector<std::uint8_t> samples;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) samples.insert(samples.end(), {r, g, b, std::uint8_t(2 * x < width ? 0 : 255)});
  return samples;
}

}  // namespace rayview::testing
