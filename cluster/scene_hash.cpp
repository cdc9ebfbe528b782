#include "scene_hash.h"

#include <cstring>
#include <optional>
#include <string>
#include <vector>

#include "rayview/scene_writer.h"

namespace rayview::cluster {
namespace {

// Word at a time: a 1M-triangle scene's 36 MB are hashed in a few milliseconds.
class Hasher {
 public:
  void add(const void* data, std::size_t bytes) {
    const auto* p = static_cast<const unsigned char*>(data);
    mix(bytes);
    if (bytes == 0) return;  // an empty array's data() may be null, which memcpy must not see
    for (; bytes >= 8; bytes -= 8, p += 8) {
      std::uint64_t word;
      std::memcpy(&word, p, 8);
      mix(word);
    }
    std::uint64_t tail = 0;
    if (bytes > 0) std::memcpy(&tail, p, bytes);
    mix(tail);
  }
  template <class T, class Allocator>
  void addArray(const std::vector<T, Allocator>& values) {
    add(values.data(), values.size() * sizeof(T));
  }
  void addText(const std::string& text) { add(text.data(), text.size()); }
  std::uint64_t value() const { return state_ ^ (state_ >> 31); }

 private:
  void mix(std::uint64_t word) {
    state_ ^= word;
    state_ = (state_ << 27 | state_ >> 37) * 0x9E3779B97F4A7C15ull + 0x632BE59BD9B4E019ull;
  }
  std::uint64_t state_ = 0xCBF29CE484222325ull;
};

void addTexture(Hasher& hasher, const std::optional<Texture>& texture) {
  if (!texture) return hasher.addText("no texture");
  const int size[2] = {texture->width, texture->height};
  hasher.add(size, sizeof size);
  hasher.add(texture->rgb.data(), texture->rgb.size());
  // A cut-out's coverage; nothing for an image without alpha, whose hash stays what it was.
  if (!texture->alpha.empty()) hasher.add(texture->alpha.data(), texture->alpha.size());
}

}  // namespace

std::uint64_t parametersHash(const SceneParameters& parameters) {
  Hasher hasher;
  hasher.addText(sceneToXml(parameters, SceneGeometry{}, std::string()));
  return hasher.value();
}

std::uint64_t sceneHash(const Scene& scene) {
  Hasher hasher;
  // The parameters through the writer: every field it saves, in its shortest exact text.
  hasher.addText(sceneToXml(scene.parameters(), SceneGeometry{}, scene.textureImage));
  hasher.addArray(scene.vertices);
  hasher.addArray(scene.texCoords);
  hasher.addArray(scene.normals);
  hasher.addArray(scene.vertexColors);
  hasher.add(scene.triangles.data(), scene.triangles.size() * sizeof(Triangle));
  hasher.add(scene.faceAttributes.data(), scene.faceAttributes.size() * sizeof(FaceAttributes));
  for (const Mesh& mesh : scene.meshes) {
    hasher.addText(mesh.id);
    const std::uint32_t fields[3] = {mesh.material, mesh.firstTriangle, mesh.triangleCount};
    hasher.add(fields, sizeof fields);
  }
  addTexture(hasher, scene.texture);
  for (const NamedTexture& named : scene.materialTextures) {
    hasher.addText(named.name);
    addTexture(hasher, named.image);
  }
  return hasher.value();
}

}  // namespace rayview::cluster
