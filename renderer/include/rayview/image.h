#pragma once
// An 8-bit RGB image, rows top to bottom, and its files (PNG or PPM by extension, written whole).

#include <cstdint>
#include <filesystem>
#include <memory>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "rayview/pixel_bytes.h"

namespace rayview {

struct Texture;  // rayview/scene.h

struct Image {
  int width = 0;
  int height = 0;
  PixelBytes rgb;  // width * height * 3

  Image() = default;
  Image(int w, int h) : width(w), height(h), rgb(static_cast<std::size_t>(w) * h * 3, 0) {}  // black
  // An image whose every pixel the caller writes before reading any: its bytes are left as the allocation gives them.
  static Image unfilled(int w, int h) {
    Image image;
    image.width = w;
    image.height = h;
    image.rgb.resize(static_cast<std::size_t>(w) * h * 3);
    return image;
  }
  std::uint8_t* pixel(int x, int y) { return &rgb[(static_cast<std::size_t>(y) * width + x) * 3]; }
  const std::uint8_t* pixel(int x, int y) const { return &rgb[(static_cast<std::size_t>(y) * width + x) * 3]; }
};

class ImageIoError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// How PNG files are deflated: `level` 1 (fastest) is ISA-L's level 1, 2 .. 9 (smallest) zlib's, in up to `threads`
// parts at once (0: one per hardware thread; parts are at least 256 KiB); rows unfiltered (png_encode.cpp). Level
// 1: the fastest measured, files 1-6 % larger than zlib's level 1 (docs/PERFORMANCE.md, "PNG writing").
inline constexpr int kDefaultPngLevel = 1;
struct PngOptions {
  int level = kDefaultPngLevel;
  int threads = 0;
};

// A file's bytes as the pieces they were made in, in order, and what keeps those alive: written one after another
// they are the file. Encoders hand their buffers over rather than gather them into one, whose fresh pages the copy
// would first touch (a 1024x768 PNG's ~70 faults, its PPM's ~580; docs/PERFORMANCE.md, "Fresh pages").
struct FileBytes {
  std::vector<std::string_view> pieces;
  std::shared_ptr<const void> owner;  // what the pieces point into; null when the caller keeps it

  FileBytes() = default;
  // `bytes` as the one piece, not owned: it must outlive this.
  static FileBytes viewOf(const std::string& bytes);
  std::size_t size() const;
  std::string joined() const;
};

// The whole PNG file (8-bit RGB). Throws ImageIoError.
FileBytes encodePngFile(const Image& image, const PngOptions& options = {});
// The same, gathered.
std::string encodePng(const Image& image, const PngOptions& options = {});

// A texture as a whole PNG file: 8-bit RGBA when it has an alpha channel (Texture::alpha or opaqueAlpha, so that a
// cut-out's image keeps its coverage), else 8-bit RGB as encodePng. Throws ImageIoError.
std::string encodeTexturePng(const Texture& texture);

// Writes to a temporary file beside `path` and renames it into place, so an existing file is never left
// half-written. Format from the extension: .png or .ppm (binary P6). Throws ImageIoError.
void writeImageFile(const std::filesystem::path& path, const Image& image);
// The same, taking the image: a PNG's pixels are freed once encoded, before the file is written; a PPM's are its bytes,
// written where they are.
void writeImageFile(const std::filesystem::path& path, Image&& image);

// Reads PNG, JPEG, binary PPM/PGM as 8-bit RGB (the values the file holds, scaled from its bit depth; refused
// when truncated or too large). The file is recorded as `role` (rayview/input_files.h), so no output replaces it.
// Throws ImageIoError.
Image readImageFile(const std::filesystem::path& path, std::string_view role = "an image this command reads");

// True when `path` has an extension writeImageFile understands.
bool isSupportedImageExtension(const std::filesystem::path& path);

// Writes `bytes` to `path` whole (temporary file + rename). Refuses a `path` that is, by any spelling or link, a
// file this process read (rayview/input_files.h) unless it was read as `mayReplaceRole`. A symlink is written
// through (its target is replaced, the link stays). The temporary name, in the same directory, never exceeds
// NAME_MAX. Throws ImageIoError.
void writeFileAtomically(const std::filesystem::path& path, const FileBytes& bytes, std::string_view mayReplaceRole = {});
void writeFileAtomically(const std::filesystem::path& path, const std::string& bytes,
                         std::string_view mayReplaceRole = {});

// Makes every catchable signal that would end the process (SIGHUP, SIGINT, SIGQUIT, SIGPIPE, SIGTERM, ..., and the
// faults: one list, renderer/temporary_cleanup.cpp) remove the temporary file being written before the process
// ends, so that an output is whole or absent. A signal already ignored or handled (nohup, a sanitizer) is left as
// it is. The asynchronous ones exit 128 + the signal, as a shell reports it.
void removeTemporaryFileOnSignals();

// The temporary file writeFileAtomically() is writing right now, or nullptr. Safe to call from a signal
// handler (a lock-free atomic and a static buffer), which can remove the file before the process exits:
// after the rename the name no longer exists, so removing it then does nothing.
const char* temporaryFileInProgress();

}  // namespace rayview
