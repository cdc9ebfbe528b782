#pragma once
// JPEG to 8-bit RGB with libjpeg-turbo (see jpeg_decode.cpp for why not stb_image).

#include <optional>
#include <string>
#include <string_view>

#include "rayview/scene.h"

namespace rayview::detail {

// A JPEG's first bytes (SOI marker).
bool looksLikeJpeg(std::string_view bytes);

// On failure returns nullopt and sets `reason` (never throws, never aborts). Images over maxPixels are
// refused from the header, before decoding.
std::optional<Texture> decodeJpeg(std::string_view bytes, long long maxPixels, std::string& reason);

}  // namespace rayview::detail
