#pragma once
// Binary PPM (P6) and PGM (P5) to 8-bit RGB, read by rayview itself (see pnm_decode.cpp for why).

#include <optional>
#include <string>
#include <string_view>

#include "rayview/scene.h"

namespace rayview::detail {

// A binary PGM or PPM's first bytes ("P5", "P6").
bool looksLikePnm(std::string_view bytes);

// On failure returns nullopt and sets `reason` (never throws). Images over maxPixels are refused from the
// header, before the samples are read.
std::optional<Texture> decodePnm(std::string_view bytes, long long maxPixels, std::string& reason);

}  // namespace rayview::detail
