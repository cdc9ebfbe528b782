#include "texture_beside.h"

#include <cstdio>
#include <system_error>

#include "rayview/image.h"

namespace rayview {

namespace fs = std::filesystem;

std::string freeTextureName(const fs::path& output) {
  const std::string stem = output.stem().string() + "_texture";
  std::error_code ec;
  std::string name = stem + ".png";
  for (int n = 2; fs::exists(output.parent_path() / name, ec) || fs::is_symlink(output.parent_path() / name, ec); ++n)
    name = stem + "-" + std::to_string(n) + ".png";
  if (name != stem + ".png")
    std::fprintf(stderr, "rayview: note: %s is taken; the texture is written as %s\n",
                 (output.parent_path() / (stem + ".png")).string().c_str(),
                 (output.parent_path() / name).string().c_str());
  return name;
}

fs::path writeTextureBeside(const Texture& texture, const fs::path& output, std::string& name) {
  name = freeTextureName(output);
  const fs::path target = output.parent_path() / name;
  Image image(texture.width, texture.height);
  image.rgb = texture.rgb;
  writeImageFile(target, std::move(image));
  return target;
}

}  // namespace rayview
