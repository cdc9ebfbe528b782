// Fuzz target "texture": the image readers (libpng, libjpeg-turbo and rayview's PPM/PGM reader behind
// renderer/texture_image.cpp) on any bytes: the <textureimage> reader and the one `rayview compare` and the
// viewer's reference use (readImageFile calls the same readTextureImage). It reads from a path, so each input is
// written to one scratch file per process first. Either it returns nullopt with a reason, or a texture whose pixel
// array matches its size, within the one image limit (rayview/image_limits.h).
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include <unistd.h>

#include "fuzz_input.h"
#include "rayview/image_limits.h"
#include "rayview/texture_image.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  namespace fs = std::filesystem;
  static const fs::path scratch =
      fs::temp_directory_path() / ("rayview-fuzz-texture-" + std::to_string(::getpid()) + ".img");
  static const bool removeAtExit = [] {
    std::atexit([] {
      std::error_code ec;
      fs::remove(scratch, ec);
    });
    return true;
  }();
  (void)removeAtExit;
  {
    std::ofstream out(scratch, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
    if (!out) rayview::fuzz::fail("cannot write the scratch file");
  }
  std::string reason;
  const auto texture = rayview::detail::readTextureImage(scratch, reason);
  if (!texture) {
    if (reason.empty()) rayview::fuzz::fail("a refused texture without a reason");
  } else {
    if (texture->width <= 0 || texture->height <= 0) rayview::fuzz::fail("a texture without pixels");
    if (texture->rgb.size() != static_cast<std::size_t>(texture->width) * texture->height * 3)
      rayview::fuzz::fail("the pixel array does not match the texture's size");
    if (!rayview::imageSizeProblem(texture->width, texture->height).empty())
      rayview::fuzz::fail("a texture over the image size limit");
  }
  return 0;
}
