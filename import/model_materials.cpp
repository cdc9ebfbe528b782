// Assimp's materials as the handout's Blinn-Phong materials (the formula is in docs/scene-format.md, "Opening
// models"), each with its own texture.

#include <assimp/GltfMaterial.h>
#include <assimp/material.h>
#include <assimp/scene.h>

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <map>
#include <optional>
#include <string>

#include "model_parts.h"
#include "rayview/metal_rough.h"
#include "rayview/texture_image.h"

namespace rayview::model {
namespace {

namespace fs = std::filesystem;

constexpr float kTextureFactor = 0.5f;  // half texel, half lit colour: the format blends rather than multiplies

Color rgb(const aiColor4D& c) { return Color(c.r, c.g, c.b); }

Color clamp01(Color c) { return glm::clamp(c, Color(0.0f), Color(1.0f)); }

// The first texture a material names of the first of `types` it has ("" when none).
std::string firstTexture(const aiMaterial& m, std::initializer_list<aiTextureType> types) {
  aiString path;
  for (const aiTextureType type : types)
    if (m.GetTextureCount(type) > 0 && m.GetTexture(type, 0, &path) == AI_SUCCESS) return path.C_Str();
  return {};
}

// The base-colour texture a material names: glTF's base colour, else the diffuse map.
std::string baseColorTexture(const aiMaterial& m) {
  return firstTexture(m, {aiTextureType_BASE_COLOR, aiTextureType_DIFFUSE});
}

// glTF's metallic and roughness factors (each 0..1), when the material has either. A material that also has glTF's
// specular-glossiness (Assimp's glossiness factor) and no metallic-roughness map is read as Phong: its specular
// colour is the file's own, where glTF's metal would make every dielectric 0.04 (so an OBJ exported to glTF, whose
// exporter writes both, opens again with the specular colour it had).
struct MetalRough {
  float metallic = 1.0f, roughness = 1.0f;
};
std::string metalRoughTexture(const aiMaterial& m);
std::optional<MetalRough> metalRoughFactors(const aiMaterial& m) {
  float glossiness = 0.0f;
  if (m.Get(AI_MATKEY_GLOSSINESS_FACTOR, glossiness) == AI_SUCCESS && metalRoughTexture(m).empty()) return std::nullopt;
  float metallic = 0.0f, roughness = 1.0f;
  const bool hasMetallic = m.Get(AI_MATKEY_METALLIC_FACTOR, metallic) == AI_SUCCESS;
  const bool hasRoughness = m.Get(AI_MATKEY_ROUGHNESS_FACTOR, roughness) == AI_SUCCESS;
  if (!hasMetallic && !hasRoughness) return std::nullopt;
  return MetalRough{std::clamp(std::isfinite(metallic) ? metallic : 0.0f, 0.0f, 1.0f),
                    std::clamp(std::isfinite(roughness) ? roughness : 1.0f, 0.0f, 1.0f)};
}

Material phongOf(const aiMaterial& m, bool& madeUpColor) {
  Material out;
  aiColor4D color;
  float value = 0.0f;
  if (m.Get(AI_MATKEY_BASE_COLOR, color) == AI_SUCCESS || m.Get(AI_MATKEY_COLOR_DIFFUSE, color) == AI_SUCCESS) {
    out.diffuse = clamp01(rgb(color));
  } else {
    out.diffuse = Color(0.8f);
    madeUpColor = true;
  }
  out.ambient = out.diffuse;
  if (const std::optional<MetalRough> factors = metalRoughFactors(m)) {
    out.baseColor = out.diffuse;
    out.metallic = factors->metallic;
    out.roughness = factors->roughness;
    setPhongTerms(out, metalRoughTerms(out.baseColor, out.metallic, out.roughness));
  } else {
    if (m.Get(AI_MATKEY_COLOR_SPECULAR, color) == AI_SUCCESS) out.specular = clamp01(rgb(color));
    float strength = 1.0f;
    if (m.Get(AI_MATKEY_SHININESS_STRENGTH, strength) == AI_SUCCESS && std::isfinite(strength) && strength >= 0.0f)
      out.specular = clamp01(out.specular * strength);
    if (m.Get(AI_MATKEY_SHININESS, value) == AI_SUCCESS && std::isfinite(value) && value > 0.0f)
      out.phongExponent = std::clamp(value, 1.0f, 10000.0f);
    float reflectivity = 0.0f;
    if (m.Get(AI_MATKEY_REFLECTIVITY, reflectivity) == AI_SUCCESS && std::isfinite(reflectivity) && reflectivity > 0.0f) {
      aiColor4D reflective(1.0f, 1.0f, 1.0f, 1.0f);
      m.Get(AI_MATKEY_COLOR_REFLECTIVE, reflective);
      out.mirror = clamp01(rgb(reflective) * std::min(reflectivity, 1.0f));
    }
  }
  // Emission as radiance on the image's scale: an emissive factor of 1 shows at full brightness, lit or not.
  if (m.Get(AI_MATKEY_COLOR_EMISSIVE, color) == AI_SUCCESS) out.emission = clamp01(rgb(color)) * 255.0f;
  return out;
}

std::string materialId(const aiMaterial& m, std::size_t index, std::map<std::string, int>& taken) {
  aiString name;
  std::string id = "material";
  if (m.Get(AI_MATKEY_NAME, name) == AI_SUCCESS && name.length > 0) id = name.C_Str();
  else id.append(std::to_string(index + 1));
  if (const int seen = taken[id]++; seen > 0) id.append(1, '_').append(std::to_string(seen + 1));
  return id;
}

// Whether `file` lies outside `dir` (and its subfolders), symbolic links followed.
bool outsideFolder(const fs::path& dir, const fs::path& file) {
  std::error_code ec;
  const fs::path folder = fs::weakly_canonical(dir.empty() ? fs::path(".") : dir, ec);
  const fs::path relative = fs::weakly_canonical(file, ec).lexically_relative(folder);
  return ec || relative.empty() || *relative.begin() == "..";
}

// A texture named by a material: embedded ("*0", or a .glb's own image by name), or a file beside the model. A file
// outside the model's folder (`../`, an absolute path) is read, with a warning naming it in `notes`: a model can
// name any image on the machine, and the user should know which one it took.
std::optional<Texture> loadTexture(const aiScene& scene, const fs::path& modelDir, const std::string& name,
                                   std::string& reason, Notes& notes, fs::path* file = nullptr) {
  if (const aiTexture* embedded = scene.GetEmbeddedTexture(name.c_str())) {
    if (!embedded->pcData) {
      reason = "the embedded image is empty";
      return std::nullopt;
    }
    if (embedded->mHeight == 0)  // compressed bytes (PNG, JPEG) of length mWidth
      return detail::decodeImage(
          std::string_view(reinterpret_cast<const char*>(embedded->pcData), embedded->mWidth), reason);
    const std::size_t pixels = static_cast<std::size_t>(embedded->mWidth) * embedded->mHeight;
    if (pixels > static_cast<std::size_t>(detail::kMaxTexturePixels)) {
      reason = "the embedded image is too large";
      return std::nullopt;
    }
    Texture t{static_cast<int>(embedded->mWidth), static_cast<int>(embedded->mHeight), {}, {}};
    t.rgb.reserve(pixels * 3);
    for (std::size_t i = 0; i < pixels; ++i)
      t.rgb.insert(t.rgb.end(), {embedded->pcData[i].r, embedded->pcData[i].g, embedded->pcData[i].b});
    // Alpha only when some texel is not opaque: an opaque image pays nothing for it.
    if (std::any_of(embedded->pcData, embedded->pcData + pixels, [](const aiTexel& texel) { return texel.a != 255; }))
      for (std::size_t i = 0; i < pixels; ++i) t.alpha.push_back(embedded->pcData[i].a);
    return t;
  }
  std::error_code ec;
  for (const fs::path& candidate : detail::textureCandidates(modelDir, name)) {
    if (!fs::is_regular_file(candidate, ec)) continue;
    std::optional<Texture> texture = detail::readTextureImage(candidate, reason);
    const fs::path literal = (fs::path(name).is_absolute() ? fs::path(name) : modelDir / name).lexically_normal();
    if (texture && outsideFolder(modelDir, candidate))
      notes.warnings.push_back("texture \"" + name + "\" is read from outside the model's folder: " +
                               fs::absolute(candidate, ec).lexically_normal().string());
    else if (texture && candidate != literal)  // a Windows path, or another machine's: the name found beside it
      notes.warnings.push_back("texture \"" + name + "\" is not where the model says; read as " + candidate.string());
    if (file) *file = candidate;
    return texture;
  }
  reason = "not found";
  return std::nullopt;
}

// The scene's name for a texture: a file outside the model's folder where it lies (absolute; `import` copies it only
// when asked), else the name of import's copy beside the scene, numbered from the second on.
std::string keptTextureName(const fs::path& model, const fs::path& file, std::size_t number) {
  std::error_code ec;
  if (!file.empty() && outsideFolder(model.parent_path(), file)) return fs::absolute(file, ec).lexically_normal().string();
  std::string name = model.stem().string() + "_texture";
  if (number > 1) name += '-' + std::to_string(number);
  return name + ".png";
}

// The metallic-roughness map a material names ("" when none): glTF's, which Assimp 5.2.5 files as UNKNOWN, or the
// metalness map of other formats.
std::string metalRoughTexture(const aiMaterial& m) {
  return firstTexture(m, {aiTextureType_UNKNOWN, aiTextureType_METALNESS});
}

std::string fileNamePart(const std::string& name) {
  const std::string base = fs::path(name).filename().string();
  return base.empty() || base[0] == '*' ? "embedded" : base;
}

// The emission map a material names ("" when none).
std::string emissionTexture(const aiMaterial& m) { return firstTexture(m, {aiTextureType_EMISSIVE}); }

// A material's cut-out, as the model names it: glTF's alpha mode MASK (its base-colour texture's alpha, at its
// alphaCutoff) or BLEND (the same, at 0.5: rayview draws no blending; `blended` set), else an opacity map (OBJ's map_d)
// at 0.5. `keep(name)` keeps an image as keepTextures does; `base` is the material's base-colour texture.
template <class Keep>
void keepCutOut(const aiMaterial& source, const std::string& base, Keep&& keep, Scene& out, Material& material,
                bool& blended) {
  aiString mode;
  const std::string alphaMode = source.Get(AI_MATKEY_GLTF_ALPHAMODE, mode) == AI_SUCCESS ? mode.C_Str() : "";
  if ((alphaMode == "MASK" || alphaMode == "BLEND") && !base.empty()) {
    const auto& image = keep(base);
    const Texture* texture = image ? out.textureNamed(image->first) : nullptr;
    if (!texture || texture->alpha.empty()) return;  // an image without alpha: opaque, as glTF reads it
    float cutoff = 0.5f;  // glTF's default; BLEND's too, here
    if (alphaMode == "MASK") source.Get(AI_MATKEY_GLTF_ALPHACUTOFF, cutoff);
    blended |= alphaMode == "BLEND";
    material.alphaImage = image->first;
    material.alphaCutoff = std::isfinite(cutoff) ? std::clamp(cutoff, 0.0f, 1.0f) : 0.5f;
    return;
  }
  const std::string opacity = firstTexture(source, {aiTextureType_OPACITY});
  if (const auto& image = opacity.empty() ? std::nullopt : keep(opacity)) {
    material.alphaImage = image->first;
    material.alphaCutoff = 0.5f;
  }
}

// A glTF material's terms once its textures are known: the base colour times the base texture's mean texel
// (`meanTexel`), and the metallic-roughness map kept per texel, its mean texel scaling the factors for the terms
// the file shows readers of the handout's format (and rayview where a hit has no texture coordinates).
void setMetalRough(Material& material, const Color& meanTexel, const std::optional<std::pair<std::string, Color>>& map) {
  material.baseColor *= meanTexel;
  MetalRough scale;
  if (map) {
    material.metalRoughImage = map->first;
    scale = {map->second.z, map->second.y};  // metallic in blue, roughness in green
  }
  setPhongTerms(material, metalRoughTerms(material.baseColor, material.metallic * scale.metallic,
                                          material.roughness * scale.roughness));
}

// Each material's base-colour texture, emission map and metallic-roughness map, kept as its own: the texture
// blended in at kTextureFactor, the material's colour times the texture's mean; the map scaling its emission (a
// map alone: emission 255). Each image is read once. Without texture coordinates none can be shown.
void keepTextures(const aiScene& scene, const fs::path& path, const std::map<unsigned, std::uint32_t>& ours,
                  Scene& out, Notes& notes) {
  std::map<std::string, std::optional<std::pair<std::string, Color>>> kept;  // the model's name -> ours, mean texel
  auto keep = [&](const std::string& name) -> const std::optional<std::pair<std::string, Color>>& {
    auto [it, added] = kept.emplace(name, std::nullopt);
    if (!added) return it->second;
    std::string reason;
    fs::path file;
    std::optional<Texture> texture = loadTexture(scene, path.parent_path(), name, reason, notes, &file);
    if (!texture) {
      notes.warnings.push_back("texture \"" + name + "\" cannot be used (" + reason + "); its material keeps its colour");
      return it->second;
    }
    notes.textures.push_back(fileNamePart(name) + " (" + std::to_string(texture->width) + "x" +
                             std::to_string(texture->height) + ")");
    it->second = std::pair{keptTextureName(path, file, out.materialTextures.size() + 1), averageOf(*texture)};
    out.materialTextures.push_back({it->second->first, std::move(texture)});
    return it->second;
  };
  bool withoutCoordinates = false, blended = false;
  for (const auto& [index, our] : ours) {
    if (index >= scene.mNumMaterials || !scene.mMaterials[index]) continue;
    const aiMaterial& source = *scene.mMaterials[index];
    const std::string base = baseColorTexture(source), glow = emissionTexture(source), metal = metalRoughTexture(source);
    withoutCoordinates |= (!base.empty() || !glow.empty() || !metal.empty()) && out.texCoords.empty();
    if (out.texCoords.empty()) continue;
    Material& material = out.materials[our];
    Color meanTexel(1.0f);
    if (const auto& image = base.empty() ? std::nullopt : keep(base)) {
      meanTexel = image->second;
      material.textureFactor = kTextureFactor;
      material.textureImage = image->first;
    }
    if (metalRoughFactors(source)) {
      setMetalRough(material, meanTexel, metal.empty() ? std::nullopt : keep(metal));
    } else {
      material.diffuse *= meanTexel;
      material.ambient = material.diffuse;
    }
    if (const auto& image = glow.empty() ? std::nullopt : keep(glow)) {
      material.emissionImage = image->first;
      if (!material.emits()) material.emission = Color(255.0f);
    }
    keepCutOut(source, base, keep, out, material, blended);
  }
  if (blended) notes.dropped.push_back("alpha blending (drawn as a cut-out at 0.5)");
  if (withoutCoordinates)
    notes.warnings.push_back("the model has textures but no texture coordinates; they are left out");
}

}  // namespace

Color averageOf(const Texture& t) {
  double sum[3] = {0.0, 0.0, 0.0};
  for (std::size_t i = 0; i + 2 < t.rgb.size(); i += 3)
    for (int c = 0; c < 3; ++c) sum[c] += t.rgb[i + static_cast<std::size_t>(c)];
  const double n = std::max<double>(1.0, static_cast<double>(t.rgb.size() / 3) * 255.0);
  return Color(static_cast<float>(sum[0] / n), static_cast<float>(sum[1] / n), static_cast<float>(sum[2] / n));
}

void mapMaterials(const aiScene& scene, const fs::path& path, Scene& out, Notes& notes) {
  // Assimp's material index -> ours, numbered in order of first use.
  std::map<unsigned, std::uint32_t> ours;
  std::map<std::string, int> taken;
  bool madeUpColor = false;
  for (Mesh& mesh : out.meshes) {
    const unsigned index = mesh.material;
    auto [it, added] = ours.emplace(index, static_cast<std::uint32_t>(out.materials.size()));
    if (added) {
      Material material;
      if (index < scene.mNumMaterials && scene.mMaterials[index]) {
        const aiMaterial& m = *scene.mMaterials[index];
        material = phongOf(m, madeUpColor);
        material.id = materialId(m, index, taken);
      } else {
        material.diffuse = material.ambient = Color(0.8f);
        material.id = std::string("material").append(std::to_string(index + 1));
        madeUpColor = true;
      }
      out.materials.push_back(std::move(material));
    }
    mesh.material = it->second;
  }
  if (madeUpColor) notes.madeUp.push_back("material colours");

  keepTextures(scene, path, ours, out, notes);
}

}  // namespace rayview::model
