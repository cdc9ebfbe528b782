// A scene as a model file through Assimp's exporters: one Assimp mesh per scene mesh, the handout's materials as
// Phong colours and shininess, each material's texture by the name the export command wrote it under.

#include <assimp/Exporter.hpp>
#include <assimp/GltfMaterial.h>
#include <assimp/material.h>
#include <assimp/scene.h>
#include <unistd.h>

#include <algorithm>
#include <map>
#include <memory>
#include <optional>
#include <system_error>

#include "checked_write.h"
#include "model_parts.h"
#include "rayview/file_names.h"
#include "rayview/model_client.h"
#include "rayview/model_import.h"

namespace rayview {
namespace {

namespace fs = std::filesystem;

std::string formatFor(const fs::path& output) {
  const std::string extension = lowerExtension(output);
  static const std::map<std::string, std::string> kFormats = {
      {".obj", "obj"}, {".ply", "plyb"}, {".stl", "stlb"}, {".gltf", "gltf2"}, {".glb", "glb2"}};
  const auto found = kFormats.find(extension);
  return found == kFormats.end() ? std::string() : found->second;
}

// `colour` divided by the texture's mean texel, channel by channel: the importer gives a textured material its colour
// times that mean (model_materials.cpp), so the written colour opens again as it was.
Color withoutMeanTexel(Color colour, const Texture& texture) {
  const Color mean = model::averageOf(texture);
  for (int c = 0; c < 3; ++c)
    if (mean[c] > 0.0f) colour[c] /= mean[c];
  return colour;
}

// The diffuse colour a textured material is written with. The formats multiply it by the texture: the colour
// without the mean texel. A wholly textured one (factor 1, the handout's 2025 files) is white, as the formats mean
// by a plain texture.
Color texturedDiffuse(const Material& m, const Texture& texture) {
  return m.textureFactor == 1.0f ? Color(1.0f) : withoutMeanTexel(m.diffuse, texture);
}

// A metallic-roughness material as glTF has it: the base colour (without the texture's mean, as the diffuse colour),
// the factors and the map, which the glTF exporter writes as pbrMetallicRoughness.
void addMetalRough(const Material& m, const Texture* texture, aiMaterial& out) {
  const Color base = texture ? withoutMeanTexel(m.baseColor, *texture) : m.baseColor;
  const aiColor4D baseColor(base.x, base.y, base.z, 1.0f);
  out.AddProperty(&baseColor, 1, AI_MATKEY_BASE_COLOR);
  out.AddProperty(&m.metallic, 1, AI_MATKEY_METALLIC_FACTOR);
  out.AddProperty(&m.roughness, 1, AI_MATKEY_ROUGHNESS_FACTOR);
  const aiString file(m.metalRoughImage);
  out.AddProperty(&file, AI_MATKEY_TEXTURE(aiTextureType_UNKNOWN, 0));  // GltfMaterial.h: the metallic-roughness map
}

// A cut-out as the formats have it: an opacity map (OBJ's map_d; glTF has none), and where the coverage is the
// material's texture's own alpha, glTF's alpha mode MASK at the cutoff. OBJ keeps no cutoff (read back at 0.5).
void addCutOut(const Material& m, const std::string& texture, aiMaterial& out) {
  const aiString file(m.alphaImage);
  out.AddProperty(&file, AI_MATKEY_TEXTURE(aiTextureType_OPACITY, 0));
  if (m.alphaImage != texture) return;
  const aiString mask("MASK");
  out.AddProperty(&mask, AI_MATKEY_GLTF_ALPHAMODE);
  out.AddProperty(&m.alphaCutoff, 1, AI_MATKEY_GLTF_ALPHACUTOFF);
}

// `texture`: the image file beside the model that a textured material names ("" for none), `image` what it holds.
aiMaterial* toAssimp(const Material& m, const std::string& texture, const Texture* image) {
  auto* out = new aiMaterial;
  const aiString name(m.id);
  out->AddProperty(&name, AI_MATKEY_NAME);
  const bool textured = !texture.empty() && image && m.textureFactor != 0.0f;
  const Color kd = textured ? texturedDiffuse(m, *image) : m.diffuse;
  const aiColor3D diffuse(kd.x, kd.y, kd.z), specular(m.specular.x, m.specular.y, m.specular.z),
      ambient(m.ambient.x, m.ambient.y, m.ambient.z), mirror(m.mirror.x, m.mirror.y, m.mirror.z);
  out->AddProperty(&diffuse, 1, AI_MATKEY_COLOR_DIFFUSE);
  if (textured) {
    const aiString file(texture);
    out->AddProperty(&file, AI_MATKEY_TEXTURE_DIFFUSE(0));
  }
  out->AddProperty(&specular, 1, AI_MATKEY_COLOR_SPECULAR);
  out->AddProperty(&ambient, 1, AI_MATKEY_COLOR_AMBIENT);
  out->AddProperty(&m.phongExponent, 1, AI_MATKEY_SHININESS);
  if (m.isMirror()) {
    const float reflectivity = std::max({m.mirror.x, m.mirror.y, m.mirror.z});
    out->AddProperty(&mirror, 1, AI_MATKEY_COLOR_REFLECTIVE);
    out->AddProperty(&reflectivity, 1, AI_MATKEY_REFLECTIVITY);
  }
  if (m.emits()) {
    const Color e = glm::clamp(m.emission / 255.0f, Color(0.0f), Color(1.0f));
    const aiColor3D emissive(e.x, e.y, e.z);
    out->AddProperty(&emissive, 1, AI_MATKEY_COLOR_EMISSIVE);
  }
  if (!m.emissionImage.empty()) {
    const aiString file(m.emissionImage);
    out->AddProperty(&file, AI_MATKEY_TEXTURE_EMISSIVE(0));
  }
  if (!m.metalRoughImage.empty()) addMetalRough(m, textured ? image : nullptr, *out);
  if (!m.alphaImage.empty()) addCutOut(m, textured ? texture : std::string(), *out);
  if (m.twoSided) {
    const int twoSided = 1;
    out->AddProperty(&twoSided, 1, AI_MATKEY_TWOSIDED);
  }
  return out;
}

// One mesh's triangles with its own vertices: shared ones kept shared, unless faces carry normals or texture
// coordinates, which Assimp keeps per vertex (then each corner is its own vertex).
aiMesh* toAssimp(const Scene& s, const Mesh& mesh, std::vector<std::uint32_t>& localOf, std::vector<std::uint32_t>& stamp,
                 std::uint32_t meshIndex) {
  auto* out = new aiMesh;
  out->mName = aiString(mesh.id);
  out->mMaterialIndex = mesh.material;
  out->mPrimitiveTypes = aiPrimitiveType_TRIANGLE;
  const std::size_t first = mesh.firstTriangle, end = s.meshEnd(mesh);
  const bool perCorner = !s.faceAttributes.empty();
  std::vector<aiVector3D> positions, normals, uvs;
  std::vector<aiColor4D> colors;
  bool anyNormal = false, anyUv = false;
  out->mNumFaces = static_cast<unsigned>(end - first);
  out->mFaces = new aiFace[out->mNumFaces];
  for (std::size_t t = first; t < end; ++t) {
    aiFace& face = out->mFaces[t - first];
    face.mNumIndices = 3;
    face.mIndices = new unsigned[3];
    const FaceAttributes& a = s.attributesOf(t);
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t v = s.triangles[t].vertex[k];
      if (!perCorner && stamp[v] == meshIndex) {
        face.mIndices[k] = localOf[v];
        continue;
      }
      face.mIndices[k] = static_cast<unsigned>(positions.size());
      stamp[v] = meshIndex;
      localOf[v] = face.mIndices[k];
      const glm::dvec3& p = s.vertices[v];
      positions.emplace_back(static_cast<float>(p.x), static_cast<float>(p.y), static_cast<float>(p.z));
      if (!s.vertexColors.empty()) colors.emplace_back(s.vertexColors[v].x, s.vertexColors[v].y, s.vertexColors[v].z, 1.0f);
      if (perCorner) {
        const glm::vec3 n = a.normal[k] != kNoIndex ? s.normals[a.normal[k]] : glm::vec3(0.0f);
        const glm::vec2 uv = a.texCoord[k] != kNoIndex ? s.texCoords[a.texCoord[k]] : glm::vec2(0.0f);
        anyNormal |= a.normal[k] != kNoIndex;
        anyUv |= a.texCoord[k] != kNoIndex;
        normals.emplace_back(n.x, n.y, n.z);
        uvs.emplace_back(uv.x, uv.y, 0.0f);
      }
    }
  }
  out->mNumVertices = static_cast<unsigned>(positions.size());
  out->mVertices = new aiVector3D[positions.size()];
  std::copy(positions.begin(), positions.end(), out->mVertices);
  if (anyNormal) {
    out->mNormals = new aiVector3D[normals.size()];
    std::copy(normals.begin(), normals.end(), out->mNormals);
  }
  if (!colors.empty()) {
    out->mColors[0] = new aiColor4D[colors.size()];
    std::copy(colors.begin(), colors.end(), out->mColors[0]);
  }
  if (anyUv) {
    out->mTextureCoords[0] = new aiVector3D[uvs.size()];
    out->mNumUVComponents[0] = 2;
    std::copy(uvs.begin(), uvs.end(), out->mTextureCoords[0]);
  }
  return out;
}

// The file a material's texture is written as: its own, else the scene's.
const std::string& textureName(const Scene& s, const Material& m) {
  return m.textureImage.empty() ? s.textureImage : m.textureImage;
}

std::unique_ptr<aiScene> toAssimp(const Scene& s) {
  auto out = std::make_unique<aiScene>();
  out->mRootNode = new aiNode("rayview");
  out->mNumMaterials = static_cast<unsigned>(std::max<std::size_t>(s.materials.size(), 1));
  out->mMaterials = new aiMaterial*[out->mNumMaterials];
  for (unsigned i = 0; i < out->mNumMaterials; ++i)
    out->mMaterials[i] = i < s.materials.size() ? toAssimp(s.materials[i], textureName(s, s.materials[i]),
                                                           s.textureOf(s.materials[i]))
                                                : toAssimp(Material{"default", Color(0.8f), Color(0.8f)}, "", nullptr);
  std::vector<const Mesh*> meshes;
  for (const Mesh& mesh : s.meshes)
    if (s.meshEnd(mesh) > mesh.firstTriangle) meshes.push_back(&mesh);
  out->mNumMeshes = static_cast<unsigned>(meshes.size());
  out->mMeshes = new aiMesh*[std::max<std::size_t>(meshes.size(), 1)];
  std::vector<std::uint32_t> localOf(s.vertices.size()), stamp(s.vertices.size(), ~0u);
  for (std::uint32_t i = 0; i < meshes.size(); ++i) out->mMeshes[i] = toAssimp(s, *meshes[i], localOf, stamp, i);
  out->mRootNode->mNumMeshes = out->mNumMeshes;
  out->mRootNode->mMeshes = new unsigned[std::max<std::size_t>(meshes.size(), 1)];
  for (unsigned i = 0; i < out->mNumMeshes; ++i) out->mRootNode->mMeshes[i] = i;
  return out;
}

// Assimp writes the file and its companions (.mtl, .bin) under names derived from the one it is given, so it
// writes into a fresh directory beside the output, and each file is then renamed into place.
void exportViaDirectory(const aiScene& scene, const std::string& format, const fs::path& output) {
  const fs::path directory = output.parent_path().empty() ? fs::path(".") : output.parent_path();
  const fs::path staging = directory / (".rayview-export-" + std::to_string(::getpid()));
  std::error_code ec;
  fs::remove_all(staging, ec);
  if (!fs::create_directory(staging, ec)) model::fail(output, "cannot write here: " + ec.message());
  Assimp::Exporter exporter;
  auto* io = new model::CheckedWriteIOSystem;  // the exporter owns it
  exporter.SetIOHandler(io);
  const bool exported = exporter.Export(&scene, format, (staging / output.filename()).string()) == AI_SUCCESS;
  if (exported && !io->failure().empty()) {
    // A staged name means nothing to the user: the reason is what they act on (free space, permissions).
    const std::string failure = io->failure();
    const std::string why = failure.substr(failure.rfind(": ") + 2);
    fs::remove_all(staging, ec);
    throw ModelWriteError(output.string() + " cannot be written: " + why + "; the files there are as they were");
  }
  if (!exported) {
    const std::string why = exporter.GetErrorString();
    fs::remove_all(staging, ec);
    model::fail(output, "cannot be written" + (why.empty() ? std::string() : ": " + why));
  }
  for (const fs::directory_entry& entry : fs::directory_iterator(staging, ec)) {
    fs::rename(entry.path(), directory / entry.path().filename(), ec);
    if (ec) {
      const std::string why = ec.message();
      fs::remove_all(staging, ec);
      model::fail(output, "cannot be written: " + why);
    }
  }
  fs::remove_all(staging, ec);
}

}  // namespace

void exportScene(const Scene& scene, const fs::path& output) {
  const std::string format = formatFor(output);
  if (format.empty()) model::fail(output, "the output must end in .obj, .ply, .stl, .gltf or .glb");
  if (scene.triangles.empty()) model::fail(output, "the scene has no triangles to write");
  exportViaDirectory(*toAssimp(scene), format, output);
}

}  // namespace rayview
