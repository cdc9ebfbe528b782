#pragma once
// The whole window as drawn (panels and image), read back from the default framebuffer.

#include "rayview/image.h"

namespace rayview {

// Reads the back buffer of the current context after drawing and before the swap; rows top to bottom.
Image readWindowPixels(int framebufferWidth, int framebufferHeight);

}  // namespace rayview
