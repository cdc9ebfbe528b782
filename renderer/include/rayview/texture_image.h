#pragma once
// Reading images a user names (a <textureimage>, a reference image to compare with): PNG, JPEG, binary
// PPM/PGM, BMP, TGA.

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "rayview/file_read.h"
#include "rayview/image_limits.h"
#include "rayview/scene.h"

namespace rayview::detail {

// Largest texture accepted, in pixels (refused before decoding, from the header alone): the one image limit.
inline constexpr long long kMaxTexturePixels = kMaxImagePixels;
// Largest texture file read, in bytes (refused from its size, before reading): 1 GiB holds the largest
// accepted image even uncompressed (2^28 pixels x 3 bytes).
inline constexpr std::uintmax_t kMaxTextureFileBytes = 1ULL << 30;

// Reads (as every user file: file_read.h) and decodes an image file to 8-bit RGB. On failure returns nullopt
// and sets `reason` (never throws). The file is recorded as `role` (rayview/input_files.h).
std::optional<Texture> readTextureImage(const std::filesystem::path& path, std::string& reason,
                                        std::string_view role = kInputRole);
// Decodes an image file's bytes: PNG with libpng, JPEG with libjpeg-turbo, binary PPM/PGM (P6, P5), BMP and TGA
// with rayview's own readers. Other formats are refused.
std::optional<Texture> decodeImage(std::string_view bytes, std::string& reason);

// Where `written` (the <textureimage> text) may be, in the order tried: next to the scene
// (sceneDirectory/written), the scene directory's ancestors up to 3 levels (for paths relative to a
// repository root), the path as written, then the file name and the last 2-3 path components (for
// absolute paths from the author's machine) in the scene directory and its ancestors; a path with backslashes
// (written on Windows) is split at them for those components. No duplicates.
std::vector<std::filesystem::path> textureCandidates(const std::filesystem::path& sceneDirectory,
                                                     const std::string& written);

}  // namespace rayview::detail
