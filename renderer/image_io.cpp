// Image files whole: PNG (png_encode.cpp) or PPM written through a temporary file renamed into place, and read
// back with the texture decoders.

#include <memory>
#include <string>
#include <utility>

#include "rayview/file_names.h"
#include "rayview/image.h"
#include "rayview/texture_image.h"

namespace rayview {
namespace {

// The PPM header, then the pixels where they are: `image` must outlive the bytes unless `owned` holds it.
FileBytes encodePpm(const Image& image, std::shared_ptr<const Image> owned = nullptr) {
  struct Pieces {
    std::string header;
    std::shared_ptr<const Image> image;
  };
  auto made = std::make_shared<Pieces>();
  made->header = "P6\n" + std::to_string(image.width) + " " + std::to_string(image.height) + "\n255\n";
  made->image = std::move(owned);
  FileBytes file;
  file.pieces = {made->header, std::string_view(reinterpret_cast<const char*>(image.rgb.data()), image.rgb.size())};
  file.owner = std::move(made);
  return file;
}

}  // namespace

bool isSupportedImageExtension(const std::filesystem::path& path) {
  const std::string ext = lowerExtension(path);
  return ext == ".png" || ext == ".ppm";
}

void writeImageFile(const std::filesystem::path& path, const Image& image) {
  const std::string ext = lowerExtension(path);
  if (ext == ".png") writeFileAtomically(path, encodePngFile(image));
  else if (ext == ".ppm") writeFileAtomically(path, encodePpm(image));
  else throw ImageIoError("cannot write " + path.string() + ": the extension must be .png or .ppm");
}

void writeImageFile(const std::filesystem::path& path, Image&& image) {
  auto owned = std::make_shared<Image>(std::move(image));
  const std::string ext = lowerExtension(path);
  if (ext != ".png" && ext != ".ppm")
    throw ImageIoError("cannot write " + path.string() + ": the extension must be .png or .ppm");
  if (ext == ".ppm") {
    const Image& pixels = *owned;
    return writeFileAtomically(path, encodePpm(pixels, std::move(owned)));  // the pixels are the file's bytes
  }
  const FileBytes bytes = encodePngFile(*owned);
  // The pixels are not needed while the file is written: their memory goes back before the write's.
  owned.reset();
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
