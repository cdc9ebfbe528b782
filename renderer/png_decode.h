#pragma once
// PNG to 8-bit RGB, and alpha when it has any, with libpng (see png_decode.cpp for why not stb_image).

#include <optional>
#include <string>
#include <string_view>

#include "rayview/scene.h"

namespace rayview::detail {

// A PNG signature.
bool looksLikePng(std::string_view bytes);

// On failure returns nullopt and sets `reason` (never throws). Images over maxPixels are refused from the
// header, before the samples are read.
std::optional<Texture> decodePng(std::string_view bytes, long long maxPixels, std::string& reason);

}  // namespace rayview::detail
