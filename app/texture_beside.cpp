#include "texture_beside.h"

#include <algorithm>
#include <cstdio>
#include <map>
#include <system_error>

#include "rayview/image.h"

namespace rayview {

namespace fs = std::filesystem;

std::string TexturesBeside::freeName() const {
  const std::string stem = output_.stem().string() + "_texture";
  const fs::path folder = output_.parent_path();
  std::error_code ec;
  std::string name = stem + ".png";
  bool userFile = false;  // a name passed over that this command did not write
  for (int n = 2; fs::exists(folder / name, ec) || fs::is_symlink(folder / name, ec); ++n) {
    userFile |= std::find(written_.begin(), written_.end(), folder / name) == written_.end();
    name = stem + "-" + std::to_string(n) + ".png";
  }
  if (userFile)
    std::fprintf(stderr, "rayview: note: a file holds the name %s; the texture is written as %s\n",
                 (folder / (stem + ".png")).string().c_str(), (folder / name).string().c_str());
  return name;
}

std::string TexturesBeside::write(const Texture& texture) {
  const std::string name = freeName();
  const fs::path target = output_.parent_path() / name;
  writeFileAtomically(target, encodeTexturePng(texture));
  written_.push_back(target);
  return name;
}

void TexturesBeside::removeAll() {
  std::error_code ec;
  for (const fs::path& file : written_) fs::remove(file, ec);
  written_.clear();
}

void renameTextures(Scene& scene, const TexturePlace& place) {
  scene.textureImage =
      scene.texture && !scene.textureImage.empty() ? place(scene.textureImage, *scene.texture, true) : "";
  if (scene.textureImage.empty()) scene.texture.reset();
  std::map<std::string, std::string> renamed;
  std::vector<NamedTexture> kept;
  for (NamedTexture& named : scene.materialTextures) {
    const std::string name = named.image ? place(named.name, *named.image, false) : "";
    renamed[named.name] = name;
    if (!name.empty()) kept.push_back({name, std::move(named.image)});
  }
  scene.materialTextures = std::move(kept);
  for (Material& material : scene.materials) {
    const bool ownTexture = !material.textureImage.empty();
    for (std::string* name : material.images())
      if (!name->empty()) *name = renamed[*name];
    if (ownTexture && material.textureImage.empty()) material.textureFactor = 0.0f;  // nothing left to show
  }
}

}  // namespace rayview
