// Image files whole: PNG (png_encode.cpp) or PPM written through a temporary file renamed into place, and read
// back with the texture decoders.

#include <string>
#include <utility>

#include "rayview/file_names.h"
#include "rayview/image.h"
#include "rayview/texture_image.h"

namespace rayview {
namespace {

std::string encodePpm(const Image& image) {
  std::string bytes = "P6\n" + std::to_string(image.width) + " " + std::to_string(image.height) + "\n255\n";
  bytes.append(reinterpret_cast<const char*>(image.rgb.data()), image.rgb.size());
  return bytes;
}

}  // namespace

bool isSupportedImageExtension(const std::filesystem::path& path) {
  const std::string ext = lowerExtension(path);
  return ext == ".png" || ext == ".ppm";
}

void writeImageFile(const std::filesystem::path& path, const Image& image) {
  const std::string ext = lowerExtension(path);
  if (ext == ".png") writeFileAtomically(path, encodePng(image));
  else if (ext == ".ppm") writeFileAtomically(path, encodePpm(image));
  else throw ImageIoError("cannot write " + path.string() + ": the extension must be .png or .ppm");
}

void writeImageFile(const std::filesystem::path& path, Image&& image) {
  Image owned = std::move(image);
  const std::string ext = lowerExtension(path);
  if (ext != ".png" && ext != ".ppm")
    throw ImageIoError("cannot write " + path.string() + ": the extension must be .png or .ppm");
  const std::string bytes = ext == ".png" ? encodePng(owned) : encodePpm(owned);
  // The pixels are not needed while the file is written: their memory goes back before the write's.
  owned = Image();
  writeFileAtomically(path, bytes);
}

Image readImageFile(const std::filesystem::path& path, std::string_view role) {
  // As textures are read: never blocking on a FIFO, sizes checked first, the same decoders.
  std::string reason;
  std::optional<Texture> texture = detail::readTextureImage(path, reason, role);
  if (!texture) throw ImageIoError("cannot read " + path.string() + ": " + reason);
  Image image;
  image.width = texture->width;
  image.height = texture->height;
  image.rgb = std::move(texture->rgb);
  return image;
}

}  // namespace rayview
