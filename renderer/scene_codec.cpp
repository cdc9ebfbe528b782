#include "rayview/scene_codec.h"

#include <cstring>
#include <type_traits>

namespace rayview {

// Resized, then copied: `insert` of a range into an empty vector trips GCC 12's -Wstringop-overflow.
void appendBytes(const void* data, std::size_t bytes, Bytes& out) {
  if (bytes == 0) return;
  const std::size_t at = out.size();
  out.resize(at + bytes);
  std::memcpy(out.data() + at, data, bytes);
}

void readBytes(const std::uint8_t* data, std::size_t size, std::size_t& at, void* to, std::size_t bytes) {
  if (bytes > size - at) throw CodecError("truncated");
  if (bytes != 0) std::memcpy(to, data + at, bytes);
  at += bytes;
}

namespace {

class Writer {
 public:
  explicit Writer(Bytes& out) : out_(out) {}
  template <class T>
  void pod(const T& value) {
    static_assert(std::is_trivially_copyable_v<T>);
    raw(&value, sizeof value);
  }
  void text(const std::string& value) {
    pod(static_cast<std::uint64_t>(value.size()));
    raw(value.data(), value.size());
  }
  template <class T, class Allocator>
  void array(const std::vector<T, Allocator>& values) {
    static_assert(std::is_trivially_copyable_v<T>);
    pod(static_cast<std::uint64_t>(values.size()));
    raw(values.data(), values.size() * sizeof(T));
  }

 private:
  void raw(const void* data, std::size_t bytes) { appendBytes(data, bytes, out_); }
  Bytes& out_;
};

class Reader {
 public:
  Reader(const std::uint8_t* data, std::size_t size, std::size_t at) : data_(data), size_(size), at_(at) {}
  template <class T>
  T pod() {
    static_assert(std::is_trivially_copyable_v<T>);
    T value;
    raw(&value, sizeof value);
    return value;
  }
  std::string text() {
    std::string value(count(1), '\0');
    raw(value.data(), value.size());
    return value;
  }
  template <class T, class Allocator = std::allocator<T>>
  std::vector<T, Allocator> array() {
    std::vector<T, Allocator> values(count(sizeof(T)));
    raw(values.data(), values.size() * sizeof(T));
    return values;
  }
  // How many items follow, each at least `minBytes` long.
  std::size_t items(std::size_t minBytes) { return count(minBytes); }
  std::size_t at() const { return at_; }

 private:
  // A count that the remaining bytes can hold: a corrupt count never allocates.
  std::size_t count(std::size_t elementBytes) {
    const auto n = pod<std::uint64_t>();
    if (n > (size_ - at_) / elementBytes) throw CodecError("truncated");
    return static_cast<std::size_t>(n);
  }
  void raw(void* out, std::size_t bytes) { readBytes(data_, size_, at_, out, bytes); }
  const std::uint8_t* data_;
  std::size_t size_;
  std::size_t at_;
};

void writeLights(Writer& w, const SceneLights& lights) {
  lights.forEachType([&](const auto& list) {
    w.pod(static_cast<std::uint64_t>(list.size()));
    for (const auto& light : list) {
      w.text(light.id);
      for (const auto& field : std::remove_cvref_t<decltype(light)>::fields()) {
        if (field.point) w.pod(light.*field.point);
        if (field.intensity) w.pod(light.*field.intensity);
      }
    }
  });
}

void readLights(Reader& r, SceneLights& lights) {
  lights.forEachType([&](auto& list) {
    using Light = LightOf<decltype(list)>;
    list.resize(r.items(sizeof(std::uint64_t)));
    for (Light& light : list) {
      light.id = r.text();
      for (const auto& field : Light::fields()) {
        if (field.point) light.*field.point = r.pod<glm::dvec3>();
        if (field.intensity) light.*field.intensity = r.pod<Color>();
      }
    }
  });
}

void writeMaterial(Writer& w, const Material& m) {
  w.text(m.id);
  w.pod(m.ambient);
  w.pod(m.diffuse);
  w.pod(m.specular);
  w.pod(m.phongExponent);
  w.pod(m.mirror);
  w.pod(m.textureFactor);
  w.pod(static_cast<std::uint8_t>(m.twoSided));
  w.text(m.textureImage);
  w.pod(m.emission);
  w.text(m.emissionImage);
  w.text(m.metalRoughImage);
  w.pod(m.baseColor);
  w.pod(m.metallic);
  w.pod(m.roughness);
  w.text(m.alphaImage);
  w.pod(m.alphaCutoff);
}

Material readMaterial(Reader& r) {
  Material m;
  m.id = r.text();
  m.ambient = r.pod<Color>();
  m.diffuse = r.pod<Color>();
  m.specular = r.pod<Color>();
  m.phongExponent = r.pod<float>();
  m.mirror = r.pod<Color>();
  m.textureFactor = r.pod<float>();
  m.twoSided = r.pod<std::uint8_t>() != 0;
  m.textureImage = r.text();
  m.emission = r.pod<Color>();
  m.emissionImage = r.text();
  m.metalRoughImage = r.text();
  m.baseColor = r.pod<Color>();
  m.metallic = r.pod<float>();
  m.roughness = r.pod<float>();
  m.alphaImage = r.text();
  m.alphaCutoff = r.pod<float>();
  return m;
}

void writeTexture(Writer& w, const std::optional<Texture>& texture) {
  w.pod(static_cast<std::uint8_t>(texture.has_value()));
  if (!texture) return;
  w.pod(texture->width);
  w.pod(texture->height);
  w.array(texture->rgb);
  w.array(texture->alpha);
  w.pod(static_cast<std::uint8_t>(texture->opaqueAlpha));
}

std::optional<Texture> readTexture(Reader& r) {
  if (r.pod<std::uint8_t>() == 0) return std::nullopt;
  Texture texture;
  texture.width = r.pod<int>();
  texture.height = r.pod<int>();
  texture.rgb = r.array<std::uint8_t, PixelAllocator<std::uint8_t>>();
  texture.alpha = r.array<std::uint8_t>();
  texture.opaqueAlpha = r.pod<std::uint8_t>() != 0;
  const std::size_t pixels = static_cast<std::size_t>(texture.width) * static_cast<std::size_t>(texture.height);
  if (texture.width < 0 || texture.height < 0 || texture.rgb.size() != pixels * 3 ||
      (!texture.alpha.empty() && texture.alpha.size() != pixels))
    throw CodecError("texture size does not match its pixels");
  return texture;
}

}  // namespace

void encodeGeometry(const SceneGeometry& g, Bytes& out) {
  Writer w(out);
  w.array(g.vertices);
  w.array(g.texCoords);
  w.array(g.normals);
  w.array(g.triangles);
  w.array(g.faceAttributes);
  w.pod(static_cast<std::uint64_t>(g.meshes.size()));
  for (const Mesh& mesh : g.meshes) {
    w.text(mesh.id);
    w.pod(mesh.material);
    w.pod(mesh.firstTriangle);
    w.pod(mesh.triangleCount);
  }
  w.array(g.vertexColors);
  w.text(g.textureImage);
  writeTexture(w, g.texture);
  w.pod(static_cast<std::uint64_t>(g.materialTextures.size()));
  for (const NamedTexture& named : g.materialTextures) {
    w.text(named.name);
    writeTexture(w, named.image);
  }
}

SceneGeometry decodeGeometry(const std::uint8_t* data, std::size_t size, std::size_t& at) {
  Reader r(data, size, at);
  SceneGeometry g;
  g.vertices = r.array<glm::dvec3, SceneArray<glm::dvec3>::allocator_type>();
  g.texCoords = r.array<glm::vec2>();
  g.normals = r.array<glm::vec3>();
  g.triangles = r.array<Triangle, SceneArray<Triangle>::allocator_type>();
  g.faceAttributes = r.array<FaceAttributes>();
  g.meshes.resize(r.items(sizeof(std::uint64_t)));
  for (Mesh& mesh : g.meshes) {
    mesh.id = r.text();
    mesh.material = r.pod<std::uint32_t>();
    mesh.firstTriangle = r.pod<std::uint32_t>();
    mesh.triangleCount = r.pod<std::uint32_t>();
  }
  g.vertexColors = r.array<Color>();
  g.textureImage = r.text();
  g.texture = readTexture(r);
  g.materialTextures.resize(r.items(sizeof(std::uint64_t)));
  for (NamedTexture& named : g.materialTextures) {
    named.name = r.text();
    named.image = readTexture(r);
  }
  at = r.at();
  return g;
}

void encodeParameters(const SceneParameters& p, Bytes& out) {
  Writer w(out);
  w.pod(p.maxRayDepth);
  w.pod(p.background);
  w.pod(static_cast<std::uint8_t>(p.shadowRayEpsilon.has_value()));
  w.pod(p.shadowRayEpsilon.value_or(0.0));
  w.pod(p.camera);
  w.pod(p.ambientLight);
  writeLights(w, p.lights);
  w.pod(static_cast<std::uint64_t>(p.materials.size()));
  for (const Material& m : p.materials) writeMaterial(w, m);
}

SceneParameters decodeParameters(const std::uint8_t* data, std::size_t size, std::size_t& at) {
  Reader r(data, size, at);
  SceneParameters p;
  p.maxRayDepth = r.pod<int>();
  p.background = r.pod<Color>();
  const bool hasEpsilon = r.pod<std::uint8_t>() != 0;
  const auto epsilon = r.pod<double>();
  if (hasEpsilon) p.shadowRayEpsilon = epsilon;
  p.camera = r.pod<Camera>();
  p.ambientLight = r.pod<Color>();
  readLights(r, p.lights);
  p.materials.resize(r.items(sizeof(std::uint64_t)));
  for (Material& m : p.materials) m = readMaterial(r);
  at = r.at();
  return p;
}

}  // namespace rayview
