#pragma once
// PNG files with an alpha channel, for the tests of cut-outs and of the decoders that keep alpha (rayview's own
// PNG writer writes RGB only).

#include <cstdint>
#include <string>
#include <vector>

namespace rayview::testing {

// A PNG of `channels` samples a pixel (2: grey and alpha, 4: RGBA), rows top to bottom.
std::string encodePngWithAlpha(int width, int height, int channels, const std::vector<std::uint8_t>& samples);

// `width` x `height` RGBA pixels of colour (r, g, b) whose left half has alpha 0 and right half 255.
std::vector<std::uint8_t> leftHalfClear(int width, int height, std::uint8_t r, std::uint8_t g, std::uint8_t b);

}  // namespace rayview::testing
