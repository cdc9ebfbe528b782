// The scene loader's checks after the walk: material references, the face index base and ranges,
// degenerate and repeated faces, the texture image.

#include "scene_loader_internal.h"

#include <array>
#include <cstdint>
#include <utility>
#include <vector>

namespace rayview::scene_loading {

void Loader::finish(const XMLElement* root) {
  const int rootLine = root->GetLineNum();
  if (cameraLine_ == 0) fail(rootLine, ceng477_ ? "no <Camera> element" : "no <camera> element");
  // The CENG477 dialect's defaults are the course parser's, the same values.
  if (!haveDepth_)
    warn(rootLine, ceng477_ ? "no <MaxRecursionDepth>: using 0 (no mirror reflections)"
                            : "no <maxraytracedepth>: using 0 (no mirror reflections)");
  if (!haveBackground_)
    warn(rootLine, ceng477_ ? "no <BackgroundColor>: using black (0 0 0)" : "no <background>: using black (0 0 0)");
  if (!haveAmbient_)
    warn(rootLine, ceng477_ ? "no <AmbientLight>: using black (0 0 0)" : "no <ambientlight>: using black (0 0 0)");

  for (PendingMesh& mesh : meshes_) {
    auto it = materialIndex_.find(mesh.materialId);
    if (it == materialIndex_.end())
      fail(mesh.materialIdLine, meshName(mesh) + ": material \"" + mesh.materialId + "\" is not defined" +
                                    definedMaterials());
  }
  resolveIndices(rootLine);
  const auto& colors = result_.scene.vertexColors;
  if (!colors.empty() && colors.size() != result_.scene.vertices.size())
    fail(colorDataLine_, "<colordata> has " + std::to_string(colors.size()) + " colours for " +
                             std::to_string(result_.scene.vertices.size()) + " vertices (one per vertex)");
  loadTexture();
}

std::string Loader::definedMaterials() const {
  const auto& materials = result_.scene.materials;
  if (materials.empty()) return " (the file defines no materials)";
  std::string list = " (defined:";
  for (std::size_t i = 0; i < materials.size() && i < 8; ++i) list += " \"" + materials[i].id + "\"";
  if (materials.size() > 8) list += " ...";
  return list + ")";
}

// 1-based (the handout) unless the indices of a kind contain 0 and never reach the count (SPEC section 2).
void Loader::resolveIndices(int rootLine) {
  Scene& scene = result_.scene;
  const std::int64_t counts[3] = {static_cast<std::int64_t>(scene.vertices.size()),
                                  static_cast<std::int64_t>(scene.texCoords.size()),
                                  static_cast<std::int64_t>(scene.normals.size())};
  const IndexRange* ranges[3] = {&vertexRange_, &textureRange_, &normalRange_};
  const char* kinds[3] = {"vertex", "texture", "normal"};
  std::int64_t base[3] = {1, 1, 1};
  std::string zeroBased;
  int zeroLine = 0;
  for (int k = 0; k < 3; ++k) {
    // The CENG477 dialect is 1-based only, as the course's parser reads it.
    if (!ceng477_ && ranges[k]->any() && ranges[k]->min == 0 && ranges[k]->max < counts[k]) {
      base[k] = 0;
      zeroBased += zeroBased.empty() ? kinds[k] : std::string(", ") + kinds[k];
      if (zeroLine == 0 || ranges[k]->firstZeroLine < zeroLine) zeroLine = ranges[k]->firstZeroLine;
    }
  }
  if (!zeroBased.empty())
    nonconforming(zeroLine ? zeroLine : rootLine,
                  "face indices are 0-based (" + zeroBased + " indices include 0 and never reach the count); "
                  "read as 0-based, the format's indices start at 1");

  SceneArray<Triangle>& triangles = scene.triangles;
  std::vector<FaceAttributes>& attributes = scene.faceAttributes;  // empty, or one per triangle
  const bool hasAttributes = !attributes.empty();
  std::size_t kept = 0;
  for (std::uint32_t m = 0; m < meshes_.size(); ++m) {
    PendingMesh& pending = meshes_[m];
    const std::uint32_t material = materialIndex_.at(pending.materialId);
    const std::uint32_t first = static_cast<std::uint32_t>(kept);
    std::size_t degenerate = 0;
    for (std::uint32_t i = 0; i < pending.triangleCount; ++i) {
      Triangle t = triangles[pending.firstTriangle + i];
      FaceAttributes a = hasAttributes ? attributes[pending.firstTriangle + i] : FaceAttributes{};
      for (int c = 0; c < 3; ++c) {
        const std::int64_t raw[3] = {t.vertex[c], a.texCoord[c], a.normal[c]};
        for (int k = 0; k < 3; ++k) {
          if (k > 0 && raw[k] < 0) continue;
          const std::int64_t index = raw[k] - base[k];
          if (index < 0 || index >= counts[k]) indexOutOfRange(pending, i * 3 + c, kinds[k], raw[k], base[k], counts[k]);
        }
        t.vertex[c] = static_cast<std::uint32_t>(raw[0] - base[0]);
        if (raw[1] >= 0) a.texCoord[c] = static_cast<std::int32_t>(raw[1] - base[1]);
        if (raw[2] >= 0) a.normal[c] = static_cast<std::int32_t>(raw[2] - base[2]);
      }
      if (isDegenerate(t)) {
        ++degenerate;
        continue;
      }
      if (hasAttributes) attributes[kept] = a;
      triangles[kept++] = t;
    }
    if (degenerate > 0)
      warn(pending.line, meshName(pending) + ": " + plural(degenerate, "degenerate triangle", "degenerate triangles") +
                             " skipped (zero area or a repeated vertex)");
    scene.meshes.push_back(Mesh{pending.id, material, first, static_cast<std::uint32_t>(kept - first)});
  }
  // No shrink_to_fit: a shrinking copy would hold every triangle twice at the load's peak, and what readFaces
  // reserved is close to what the text holds (detail::estimatedItems). It matters even unwritten: on the heap's
  // huge pages a reserve six times too large pushed the BVH and the image past memory the load had freed, 10 MB
  // more at the peak of a 1e5-triangle scene (docs/PERFORMANCE.md, "The loader").
  triangles.resize(kept);
  if (hasAttributes) attributes.resize(kept);
  warnAboutDuplicatedFaces();
}

// Faces listed twice (same three vertices, any order or winding) are coincident surfaces: which one a
// ray sees is a tie, which rayview gives to the face listed first. Real files do this (a wall written once
// as a mirror and once as a colour), and the picture then depends on that rule: say so.
// A face repeats when an earlier face has its three vertices. The faces go in order into an open-addressed set of
// face indices keyed by their sorted vertices: linear time and 6-12 bytes per face, where sorting 16-byte keys took
// 6 ms of killeroo_2020's load (92 000 faces) and 16 bytes per face at the load's peak.
void Loader::warnAboutDuplicatedFaces() {
  const SceneArray<Triangle>& triangles = result_.scene.triangles;
  if (triangles.size() < 2) return;
  using Key = std::array<std::uint32_t, 3>;
  auto keyOf = [&](std::uint32_t face) {
    Key k{triangles[face].vertex[0], triangles[face].vertex[1], triangles[face].vertex[2]};
    if (k[0] > k[1]) std::swap(k[0], k[1]);
    if (k[1] > k[2]) std::swap(k[1], k[2]);
    if (k[0] > k[1]) std::swap(k[0], k[1]);
    return k;
  };
  int bits = 1;  // slots: a power of two, at most two thirds full
  while ((std::size_t{1} << bits) < triangles.size() + triangles.size() / 2) ++bits;
  BigArray<std::uint32_t> slots(std::size_t{1} << bits, 0);  // face index + 1; 0: empty
  const std::size_t mask = slots.size() - 1;
  std::size_t repeats = 0;
  std::uint32_t firstRepeat = 0;  // faces come in order: the first repeat found is the earliest
  for (std::uint32_t face = 0; face < triangles.size(); ++face) {
    const Key key = keyOf(face);
    const std::uint64_t hash =
        ((std::uint64_t{key[0]} * 0x9E3779B97F4A7C15ull + key[1]) * 0x9E3779B97F4A7C15ull + key[2]) * 0x9E3779B97F4A7C15ull;
    for (std::size_t slot = static_cast<std::size_t>(hash >> (64 - bits));; slot = (slot + 1) & mask) {
      if (slots[slot] == 0) {
        slots[slot] = face + 1;
        break;
      }
      if (keyOf(slots[slot] - 1) == key) {
        if (repeats++ == 0) firstRepeat = face;
        break;
      }
    }
  }
  if (repeats == 0) return;
  const PendingMesh& mesh = meshes_[result_.scene.meshOf(firstRepeat)];
  warn(mesh.line, plural(repeats, "face repeats", "faces repeat") +
                      " the three vertices of an earlier face (the first in " + meshName(mesh) +
                      "): coincident surfaces, where rayview shows the face listed first");
}

bool Loader::isDegenerate(const Triangle& t) const {
  if (t.vertex[0] == t.vertex[1] || t.vertex[1] == t.vertex[2] || t.vertex[0] == t.vertex[2]) return true;
  const auto& v = result_.scene.vertices;
  const glm::dvec3 n = glm::cross(v[t.vertex[1]] - v[t.vertex[0]], v[t.vertex[2]] - v[t.vertex[0]]);
  if (!std::isfinite(n.x) || !std::isfinite(n.y) || !std::isfinite(n.z)) return true;
  return n.x == 0.0 && n.y == 0.0 && n.z == 0.0;
}

// Finds the line of the corner-th index token of the mesh's <faces> (only on this error path).
void Loader::indexOutOfRange(const PendingMesh& mesh, std::size_t corner, const char* kind, std::int64_t raw,
                                  std::int64_t base, std::int64_t count) {
  int line = mesh.faces->GetLineNum();
  std::size_t seen = 0;
  for (const Piece& piece : textOf(mesh.faces)) {
    detail::TokenScanner scanner(piece.text);
    for (std::string_view token = scanner.nextToken(); !token.empty(); token = scanner.nextToken())
      if (seen++ == corner) {
        line = lineIn(piece, token.data());
        goto found;
      }
  }
found:
  const char* data = kind[0] == 'v' ? "vertices" : (kind[0] == 't' ? "<texturedata> coordinates" : "<normaldata> normals");
  std::string range = count == 0 ? std::string("the file has no ") + data
                                 : "the file has " + std::to_string(count) + " " + data + ", indices " +
                                       std::to_string(base) + ".." + std::to_string(count - 1 + base) +
                                       (base == 0 ? ", read as 0-based" : "");
  fail(line, meshName(mesh) + ": " + kind + " index " + std::to_string(raw) + " is out of range (" + range + ")");
}

void Loader::loadTexture() {
  Scene& scene = result_.scene;
  for (const auto& [name, line] : materialTextureLines_)
    scene.materialTextures.push_back(
        {name, options_.loadTexture ? readTextureNamed(name, line, kMaterialTextureRole) : std::nullopt});
  if (scene.textureImage.empty() || !options_.loadTexture) return;
  scene.texture = readTextureNamed(scene.textureImage, textureImageLine_, kTextureRole);
}

std::optional<Texture> Loader::readTextureNamed(const std::string& name, int line, std::string_view role) {
  std::string tried;
  std::string lastReason;
  for (const fs::path& candidate : detail::textureCandidates(baseDirectory_, name)) {
    std::string reason;
    if (auto texture = detail::readTextureImage(candidate, reason, role)) return texture;
    if (reason != "not found") lastReason = candidate.string() + ": " + reason + "; ";
    tried += (tried.empty() ? "" : ", ") + candidate.string();
  }
  warn(line, "texture image \"" + name + "\" could not be read (" + lastReason + "tried " + tried +
                 "); rendering without the texture");
  return std::nullopt;
}

}  // namespace rayview::scene_loading
