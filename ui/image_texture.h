#pragma once
// The displayed frame as an OpenGL texture: uploaded only when a newer frame version arrives, magnified with
// nearest filtering so coarse preview passes stay crisp blocks (never blurred), minified linearly (smooth when
// the image is shown smaller than 1:1).

#include <cstdint>

#include "rayview/image.h"

namespace rayview {

class ImageTexture {
 public:
  ImageTexture();  // needs the GL context to be current
  ~ImageTexture();
  ImageTexture(const ImageTexture&) = delete;
  ImageTexture& operator=(const ImageTexture&) = delete;

  // Uploads `image` unless `version` is the one already on the GPU. Returns true when it uploaded.
  bool update(const Image& image, std::uint64_t version);

  unsigned int id() const { return texture_; }
  int width() const { return width_; }
  int height() const { return height_; }
  bool empty() const { return width_ == 0 || height_ == 0; }

 private:
  unsigned int texture_ = 0;
  int width_ = 0;
  int height_ = 0;
  std::uint64_t version_ = 0;
  bool uploaded_ = false;
};

}  // namespace rayview
