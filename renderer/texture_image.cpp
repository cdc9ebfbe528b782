#include "texture_image.h"

#include <algorithm>
#include <cstdio>
#include <memory>

#include "rayview/file_read.h"

#include "jpeg_decode.h"

// The one translation unit of the project that compiles stb_image: PNG, binary PNM, BMP and TGA. JPEG goes to
// libjpeg-turbo (jpeg_decode.cpp). GIF, PSD, HDR and PIC are left out: no scene uses them, and fuzzing found
// a 391-byte GIF that made stb_image allocate over 2 GiB.
#define STB_IMAGE_IMPLEMENTATION
#define STBI_NO_STDIO_DEPRECATION
#define STBI_NO_JPEG
#define STBI_NO_GIF
#define STBI_NO_PSD
#define STBI_NO_HDR
#define STBI_NO_PIC
#include <stb_image.h>

namespace rayview::detail {

namespace fs = std::filesystem;

std::optional<Texture> readTextureImage(const fs::path& path, std::string& reason) {
  // The size is checked before reading and the file is never opened for a blocking read (file_read.h).
  UserFileRead file = readUserFile(path, kMaxTextureFileBytes);
  if (file.notFound) {
    reason = "not found";
    return std::nullopt;
  }
  if (!file.problem.empty()) {
    reason = file.problem;
    return std::nullopt;
  }
  return decodeImage(file.bytes, reason);
}

std::optional<Texture> decodeImage(std::string_view data, std::string& reason) {
  if (data.size() > kMaxTextureFileBytes) {
    reason = "image file too large";
    return std::nullopt;
  }
  if (looksLikeJpeg(data)) return decodeJpeg(data, kMaxTexturePixels, reason);
  const auto* bytes = reinterpret_cast<const stbi_uc*>(data.data());
  const int length = static_cast<int>(data.size());  // kMaxTextureFileBytes fits an int
  int width = 0, height = 0, channels = 0;
  if (!stbi_info_from_memory(bytes, length, &width, &height, &channels)) {
    reason = std::string("not a readable image (") + stbi_failure_reason() + ")";
    return std::nullopt;
  }
  if (width <= 0 || height <= 0 || static_cast<long long>(width) * height > kMaxTexturePixels) {
    reason = "image too large (" + std::to_string(width) + " x " + std::to_string(height) + ")";
    return std::nullopt;
  }
  const std::size_t values = static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 3;
  Texture texture;
  if (stbi_is_16_bit_from_memory(bytes, length)) {
    // 16-bit images (PNG, PGM/PPM) are read as 16 bits with their own channel count and widened to RGB and
    // narrowed here: stb_image's own widening of 16-bit grey treats the samples as bytes and its narrowing
    // then reads past the buffer (found by fuzzing; tests/fuzz_regressions/texture/).
    int own = 0;
    std::unique_ptr<stbi_us, void (*)(void*)> wide(stbi_load_16_from_memory(bytes, length, &width, &height, &own, 0),
                                                  &stbi_image_free);
    if (!wide || own < 1 || own > 4) {
      reason = std::string("cannot be decoded (") + (wide ? "unexpected channel count" : stbi_failure_reason()) + ")";
      return std::nullopt;
    }
    texture.rgb.resize(values);
    const std::size_t pixelCount = values / 3;
    for (std::size_t p = 0; p < pixelCount; ++p) {
      const stbi_us* in = wide.get() + p * static_cast<std::size_t>(own);
      for (int c = 0; c < 3; ++c) texture.rgb[p * 3 + c] = static_cast<std::uint8_t>((own >= 3 ? in[c] : in[0]) >> 8);
    }
  } else {
    std::unique_ptr<stbi_uc, void (*)(void*)> pixels(stbi_load_from_memory(bytes, length, &width, &height, &channels, 3),
                                                     &stbi_image_free);
    if (!pixels) {
      reason = std::string("cannot be decoded (") + stbi_failure_reason() + ")";
      return std::nullopt;
    }
    texture.rgb.assign(pixels.get(), pixels.get() + values);
  }
  texture.width = width;
  texture.height = height;
  return texture;
}

std::vector<fs::path> textureCandidates(const fs::path& sceneDirectory, const std::string& written) {
  std::vector<fs::path> out;
  auto add = [&](const fs::path& p) {
    fs::path normal = p.lexically_normal();
    if (normal.empty()) return;
    if (std::find(out.begin(), out.end(), normal) == out.end()) out.push_back(normal);
  };
  const fs::path asWritten(written);
  const fs::path dir = sceneDirectory.empty() ? fs::path(".") : sceneDirectory;
  const std::vector<fs::path> bases{dir, dir / "..", dir / ".." / "..", dir / ".." / ".." / ".."};
  if (asWritten.is_relative())
    for (const fs::path& b : bases) add(b / asWritten);
  add(asWritten);
  // Trailing components of the path: "capsule0.jpg", "textures/capsule0.jpg", "hw1/textures/capsule0.jpg".
  std::vector<fs::path> parts;
  for (const fs::path& part : asWritten.relative_path()) parts.push_back(part);
  for (std::size_t k = 1; k <= std::min<std::size_t>(3, parts.size()); ++k) {
    fs::path tail;
    for (std::size_t i = parts.size() - k; i < parts.size(); ++i) tail /= parts[i];
    for (const fs::path& b : bases) add(b / tail);
  }
  return out;
}

}  // namespace rayview::detail
