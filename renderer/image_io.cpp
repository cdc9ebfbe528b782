#include <algorithm>
#include <atomic>
#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <random>
#include <system_error>

#include <stb_image.h>
#define STB_IMAGE_WRITE_IMPLEMENTATION
#define STBI_WRITE_NO_STDIO
#include <stb_image_write.h>

#include "rayview/image.h"

namespace rayview {
namespace {

std::string lowerExtension(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext;
}

void appendBytes(void* context, void* data, int size) {
  static_cast<std::string*>(context)->append(static_cast<const char*>(data), static_cast<std::size_t>(size));
}

std::string encodePng(const Image& image) {
  std::string bytes;
  if (!stbi_write_png_to_func(appendBytes, &bytes, image.width, image.height, 3, image.rgb.data(),
                              image.width * 3))
    throw ImageIoError("cannot encode the PNG image");
  return bytes;
}

std::string encodePpm(const Image& image) {
  std::string bytes = "P6\n" + std::to_string(image.width) + " " + std::to_string(image.height) + "\n255\n";
  bytes.append(reinterpret_cast<const char*>(image.rgb.data()), image.rgb.size());
  return bytes;
}

// One write at a time registers its temporary file here (the command line writes one image).
char g_temporaryPath[4096];
std::atomic<bool> g_temporaryActive{false};

}  // namespace

const char* temporaryFileInProgress() { return g_temporaryActive.load() ? g_temporaryPath : nullptr; }

bool isSupportedImageExtension(const std::filesystem::path& path) {
  const std::string ext = lowerExtension(path);
  return ext == ".png" || ext == ".ppm";
}

void writeFileAtomically(const std::filesystem::path& path, const std::string& bytes) {
  std::filesystem::path temporary = path;
  temporary += ".tmp-" + std::to_string(std::random_device{}());
  // Registered before the file exists, cleared after it is renamed or removed.
  const bool registered = temporary.native().size() < sizeof g_temporaryPath && !g_temporaryActive.load();
  if (registered) {
    std::memcpy(g_temporaryPath, temporary.c_str(), temporary.native().size() + 1);
    g_temporaryActive.store(true);
  }
  struct Unregister {
    bool registered;
    ~Unregister() {
      if (registered) g_temporaryActive.store(false);
    }
  } unregister{registered};
  {
    std::FILE* file = std::fopen(temporary.c_str(), "wb");
    if (!file) throw ImageIoError("cannot write " + path.string() + ": " + std::strerror(errno));
    const bool written = std::fwrite(bytes.data(), 1, bytes.size(), file) == bytes.size();
    const bool closed = std::fclose(file) == 0;
    if (!written || !closed) {
      const int error = errno;
      std::remove(temporary.c_str());
      throw ImageIoError("cannot write " + path.string() + ": " + std::strerror(error));
    }
  }
  std::error_code ec;
  std::filesystem::rename(temporary, path, ec);
  if (ec) {
    std::remove(temporary.c_str());
    throw ImageIoError("cannot write " + path.string() + ": " + ec.message());
  }
}

void writeImageFile(const std::filesystem::path& path, const Image& image) {
  const std::string ext = lowerExtension(path);
  if (ext == ".png") writeFileAtomically(path, encodePng(image));
  else if (ext == ".ppm") writeFileAtomically(path, encodePpm(image));
  else throw ImageIoError("cannot write " + path.string() + ": the extension must be .png or .ppm");
}

Image readImageFile(const std::filesystem::path& path) {
  int width = 0, height = 0, channels = 0;
  stbi_uc* pixels = stbi_load(path.c_str(), &width, &height, &channels, 3);
  if (!pixels) throw ImageIoError("cannot read " + path.string() + ": " + stbi_failure_reason());
  Image image(width, height);
  std::memcpy(image.rgb.data(), pixels, image.rgb.size());
  stbi_image_free(pixels);
  return image;
}

}  // namespace rayview
