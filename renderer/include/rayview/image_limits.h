#pragma once
// The one limit on the size of an image rayview makes or reads (a scene's resolution, a texture, an image to
// compare, the trade-off bench's scaled camera), checked from the declared size before anything is allocated.

#include <string>

namespace rayview {

// 16384 x 16384 pixels: the image (3 bytes a pixel), its accumulation buffer (16) and a reader's rows fit in a
// few GiB.
inline constexpr long long kMaxImagePixels = 1LL << 28;
// A side's limit: every per-row and per-tile structure stays bounded too (a 1 x 268435456 image would be 16
// million tiles of one column).
inline constexpr long long kMaxImageSide = 1LL << 16;

// Why a `width` x `height` image cannot be made ("" when it can): a side is not positive, or the image is over
// kMaxImageSide a side or kMaxImagePixels in all. The text starts with the size: "1 x 268435456 pixels is too
// large (the limit is 268435456 pixels, 16384 x 16384, and 65536 a side)".
std::string imageSizeProblem(long long width, long long height);

}  // namespace rayview
