#pragma once
// TGA and BMP to 8-bit RGB, read by rayview itself (the textures of many model packages; see pnm_decode.cpp for
// why not stb_image). TGA: true-colour and grey, plain or run-length encoded, 8/16/24/32 bits. BMP: 24 and 32
// bits, plain or with bit fields, and 1/4/8-bit palettes, uncompressed. Other variants are refused with a reason.

#include <optional>
#include <string>
#include <string_view>

#include "rayview/scene.h"

namespace rayview::detail {

// A BMP's first bytes ("BM").
bool looksLikeBmp(std::string_view bytes);
// A TGA has no magic number: its header's image type, colour map and pixel size are checked for a plausible one.
bool looksLikeTga(std::string_view bytes);

// On failure they return nullopt and set `reason` (never throw). Images over maxPixels are refused from the
// header, before the pixels are read.
std::optional<Texture> decodeBmp(std::string_view bytes, long long maxPixels, std::string& reason);
std::optional<Texture> decodeTga(std::string_view bytes, long long maxPixels, std::string& reason);

}  // namespace rayview::detail
