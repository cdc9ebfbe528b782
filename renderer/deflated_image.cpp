#include "rayview/deflated_image.h"

#include <zlib.h>

#include <algorithm>
#include <new>

namespace rayview {

std::string DeflatedImage::deflateRows(const std::uint8_t* rgb, int width, int rows) {
  const uLong size = static_cast<uLong>(width) * static_cast<uLong>(rows) * 3;
  // Into a scratch buffer of the bound, kept in an exact-sized string: the chunk holds what deflate gave.
  thread_local std::vector<Bytef> scratch;
  scratch.resize(compressBound(size));
  uLongf length = static_cast<uLongf>(scratch.size());
  // Level 1, zlib's fastest: the chunks live only until the write.
  if (compress2(scratch.data(), &length, rgb, size, 1) != Z_OK) throw std::bad_alloc();
  return std::string(reinterpret_cast<const char*>(scratch.data()), length);
}

Image DeflatedImage::inflate() const {
  Image image(width, height);
  const std::size_t rowBytes = static_cast<std::size_t>(width) * 3;
  int row = 0;
  for (const std::string& chunk : chunks) {
    const int rows = std::min(chunkRows, height - row);
    uLongf length = static_cast<uLongf>(rowBytes * static_cast<std::size_t>(rows));
    const uLongf expected = length;
    if (rows <= 0 || uncompress(image.pixel(0, row), &length, reinterpret_cast<const Bytef*>(chunk.data()),
                                static_cast<uLong>(chunk.size())) != Z_OK ||
        length != expected)
      throw ImageIoError("a rendered image's rows did not inflate to their size");
    row += rows;
  }
  if (row != height) throw ImageIoError("a rendered image is missing rows");
  return image;
}

}  // namespace rayview
