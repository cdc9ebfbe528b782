#include "window_capture.h"

#include <cstring>

#include <GL/gl.h>

namespace rayview {

Image readWindowPixels(int framebufferWidth, int framebufferHeight) {
  Image image(framebufferWidth, framebufferHeight);
  if (framebufferWidth <= 0 || framebufferHeight <= 0) return image;
  std::vector<std::uint8_t> bottomUp(image.rgb.size());
  glReadBuffer(GL_BACK);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, framebufferWidth, framebufferHeight, GL_RGB, GL_UNSIGNED_BYTE, bottomUp.data());
  // OpenGL's rows start at the bottom; image files start at the top.
  const std::size_t row = static_cast<std::size_t>(framebufferWidth) * 3;
  for (int y = 0; y < framebufferHeight; ++y)
    std::memcpy(image.pixel(0, y), &bottomUp[static_cast<std::size_t>(framebufferHeight - 1 - y) * row], row);
  return image;
}

}  // namespace rayview
