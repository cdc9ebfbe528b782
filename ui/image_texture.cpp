#include "image_texture.h"

#include <GL/gl.h>

namespace rayview {

ImageTexture::ImageTexture() {
  glGenTextures(1, &texture_);
  glBindTexture(GL_TEXTURE_2D, texture_);
  // Shown smaller than 1:1 an image is smoothed (each screen pixel blends the texels it covers); shown larger, its
  // pixels (and a coarse pass's blocks) stay crisp squares.
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
}

ImageTexture::~ImageTexture() { glDeleteTextures(1, &texture_); }

bool ImageTexture::update(const Image& image, std::uint64_t version) {
  if (uploaded_ && version == version_) return false;
  if (image.width <= 0 || image.height <= 0) return false;
  glBindTexture(GL_TEXTURE_2D, texture_);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);  // rows of 3-byte pixels are not 4-byte aligned
  if (image.width != width_ || image.height != height_) {
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGB8, image.width, image.height, 0, GL_RGB, GL_UNSIGNED_BYTE, image.rgb.data());
    width_ = image.width;
    height_ = image.height;
  } else {
    glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, image.width, image.height, GL_RGB, GL_UNSIGNED_BYTE, image.rgb.data());
  }
  version_ = version;
  uploaded_ = true;
  return true;
}

}  // namespace rayview
