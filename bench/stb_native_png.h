#pragma once
// stb_image_write's own PNG path (its deflate, not rayview's), for png_bench's before/after comparison.

#include <string>

#include "rayview/image.h"

namespace rayview::bench {

// The PNG as rayview wrote it before its own encoder: stb's filter choice (`filter` -1: best of five per row) and
// stb's deflate at `level` (stb treats anything below 5 as 5; its default is 8).
std::string stbNativePng(const Image& image, int level, int filter);

// stb's deflate of `bytes` bytes, discarding the result; returns the compressed size.
int stbNativeDeflate(const unsigned char* data, int bytes, int level);

}  // namespace rayview::bench
