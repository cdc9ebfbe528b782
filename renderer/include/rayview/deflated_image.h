#pragma once
// An 8-bit RGB image held deflated, in chunks of rows: what a lean render keeps while it renders (lean_memory.h).
// The soup of 1e5 triangles at 1920x1080 keeps ~1 MB this way instead of the image's 6.2 MB.

#include <cstdint>
#include <string>
#include <vector>

#include "rayview/image.h"

namespace rayview {

struct DeflatedImage {
  int width = 0;
  int height = 0;
  int chunkRows = 0;                 // every chunk's rows but the last's
  std::vector<std::string> chunks;   // zlib streams of rows [k * chunkRows, ...), top to bottom

  // `rows` rows of `rgb` (rows * width * 3 bytes), deflated: a chunk. Throws std::bad_alloc.
  static std::string deflateRows(const std::uint8_t* rgb, int width, int rows);
  // The whole image. Throws ImageIoError if a chunk does not inflate to its rows (a bug, not bad input).
  Image inflate() const;
};

}  // namespace rayview
