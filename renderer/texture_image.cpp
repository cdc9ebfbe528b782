#include "rayview/texture_image.h"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <memory>

#include "rayview/file_read.h"

#include "jpeg_decode.h"
#include "png_decode.h"
#include "pnm_decode.h"
#include "tga_bmp_decode.h"

namespace rayview::detail {

namespace fs = std::filesystem;

std::optional<Texture> readTextureImage(const fs::path& path, std::string& reason, std::string_view role) {
  // The size is checked before reading and the file is never opened for a blocking read (file_read.h).
  UserFileRead file = readUserFile(path, kMaxTextureFileBytes, {}, role);
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

// Images are decoded by libpng, libjpeg-turbo and rayview's own PNM, BMP and TGA readers, not stb_image: fuzzing found
// Debian 12's stb_image writing out of bounds (JPEG Huffman tables, 16-bit PGM), overflowing (PNM headers),
// passing null pointers to memcpy (PNG) and allocating over 2 GiB for a 391-byte GIF. The reproducers are
// replayed by ctest (tests/fuzz_regressions/texture/).
std::optional<Texture> decodeImage(std::string_view data, std::string& reason) {
  if (data.size() > kMaxTextureFileBytes) {
    reason = "image file too large";
    return std::nullopt;
  }
  if (looksLikePng(data)) return decodePng(data, kMaxTexturePixels, reason);
  if (looksLikeJpeg(data)) return decodeJpeg(data, kMaxTexturePixels, reason);
  if (looksLikePnm(data)) return decodePnm(data, kMaxTexturePixels, reason);
  if (looksLikeBmp(data)) return decodeBmp(data, kMaxTexturePixels, reason);
  if (looksLikeTga(data)) return decodeTga(data, kMaxTexturePixels, reason);  // last: TGA has no magic number
  reason = "not a readable image (rayview reads PNG, JPEG, binary PPM/PGM, BMP and TGA)";
  return std::nullopt;
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
  // Trailing components of the path: "capsule0.jpg", "textures/capsule0.jpg", "hw1/textures/capsule0.jpg". A path
  // written on Windows (".\\tex.jpg", "D:\\models\\tex.jpg") is one component here: its own separators split it.
  std::string portable = written;
  if (portable.find('\\') != std::string::npos) {
    std::replace(portable.begin(), portable.end(), '\\', '/');
    if (portable.size() >= 2 && std::isalpha(static_cast<unsigned char>(portable[0])) && portable[1] == ':')
      portable.erase(0, 2);
  }
  std::vector<fs::path> parts;
  for (const fs::path& part : fs::path(portable).relative_path())
    if (part != ".") parts.push_back(part);
  for (std::size_t k = 1; k <= std::min<std::size_t>(3, parts.size()); ++k) {
    fs::path tail;
    for (std::size_t i = parts.size() - k; i < parts.size(); ++i) tail /= parts[i];
    for (const fs::path& b : bases) add(b / tail);
  }
  return out;
}

}  // namespace rayview::detail
