// Assimp's meshes, instanced by its node tree, into one SceneGeometry.

#include <assimp/scene.h>

#include <cmath>
#include <limits>
#include <utility>

#include "model_parts.h"
#include "rayview/diagnostics.h"

namespace rayview::model {
namespace {

namespace fs = std::filesystem;

// Vertex indices are 32-bit in Triangle and the face attributes' indices signed 32-bit.
constexpr std::size_t kMaxItems = static_cast<std::size_t>(std::numeric_limits<std::int32_t>::max());

bool isIdentity(const aiMatrix4x4& m) { return m.IsIdentity(); }

struct MeshCounts {
  std::size_t pointsAndLines = 0;
  std::size_t trianglesWithBadNormals = 0;
};

class Gatherer {
 public:
  Gatherer(const aiScene& scene, const fs::path& path, SceneGeometry& geometry)
      : scene_(scene), path_(path), g_(geometry) {}

  void node(const aiNode& node, const aiMatrix4x4& world) {
    for (unsigned i = 0; i < node.mNumMeshes; ++i) {
      if (node.mMeshes[i] >= scene_.mNumMeshes || !scene_.mMeshes[node.mMeshes[i]])
        fail(path_, "a node names mesh " + std::to_string(node.mMeshes[i]) + ", which the file does not have");
      mesh(*scene_.mMeshes[node.mMeshes[i]], world);
    }
  }
  const MeshCounts& counts() const { return counts_; }

 private:
  void mesh(const aiMesh& m, const aiMatrix4x4& world) {
    if (m.mNumVertices == 0 || !m.mVertices || m.mNumFaces == 0) return;
    if (g_.vertices.size() + m.mNumVertices > kMaxItems) fail(path_, "too many vertices (over 2^31)");
    const std::size_t base = g_.vertices.size();
    const bool moved = !isIdentity(world);
    g_.vertices.reserve(base + m.mNumVertices);
    for (unsigned i = 0; i < m.mNumVertices; ++i) {
      const aiVector3D p = moved ? world * m.mVertices[i] : m.mVertices[i];
      if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
        fail(path_, "vertex " + std::to_string(i + 1) + " of mesh \"" + m.mName.C_Str() + "\" is not a finite number");
      g_.vertices.emplace_back(p.x, p.y, p.z);
    }
    colors(m, base);
    const std::int32_t normalBase = normals(m, world);
    const std::int32_t uvBase = texCoords(m);
    Mesh mesh;
    mesh.id = m.mName.length > 0 ? std::string(m.mName.C_Str()) : "mesh" + std::to_string(g_.meshes.size() + 1);
    mesh.material = m.mMaterialIndex;
    mesh.firstTriangle = static_cast<std::uint32_t>(g_.triangles.size());
    for (unsigned f = 0; f < m.mNumFaces; ++f) face(m, m.mFaces[f], base, normalBase, uvBase);
    mesh.triangleCount = static_cast<std::uint32_t>(g_.triangles.size() - mesh.firstTriangle);
    if (mesh.triangleCount > 0) g_.meshes.push_back(std::move(mesh));
  }

  // A polygon Assimp left whole is cut into a fan; points and lines are counted and left out.
  void face(const aiMesh& m, const aiFace& f, std::size_t base, std::int32_t normalBase, std::int32_t uvBase) {
    if (f.mNumIndices == 0 || !f.mIndices)  // a face a reader left empty, having found it broken
      fail(path_, "a face of mesh \"" + std::string(m.mName.C_Str()) + "\" has no vertices (broken in the file)");
    if (f.mNumIndices < 3) {
      ++counts_.pointsAndLines;
      return;
    }
    for (unsigned k = 0; k < f.mNumIndices; ++k)
      if (f.mIndices[k] >= m.mNumVertices)
        fail(path_, "a face of mesh \"" + std::string(m.mName.C_Str()) + "\" names vertex " +
                        std::to_string(f.mIndices[k]) + " of " + std::to_string(m.mNumVertices));
    for (unsigned k = 1; k + 1 < f.mNumIndices; ++k) {
      if (g_.triangles.size() >= kMaxItems) fail(path_, "too many triangles (over 2^31)");
      const unsigned corner[3] = {f.mIndices[0], f.mIndices[k], f.mIndices[k + 1]};
      Triangle t;
      FaceAttributes a;
      bool badNormal = false;
      for (int c = 0; c < 3; ++c) {
        t.vertex[c] = static_cast<std::uint32_t>(base + corner[c]);
        if (normalBase >= 0) a.normal[c] = normalBase + static_cast<std::int32_t>(corner[c]);
        if (uvBase >= 0) a.texCoord[c] = uvBase + static_cast<std::int32_t>(corner[c]);
        badNormal |= normalBase >= 0 && badNormal_[corner[c]];
      }
      if (badNormal) {  // a normal of no length costs only the triangles that use it their normals
        for (std::int32_t& n : a.normal) n = kNoIndex;
        ++counts_.trianglesWithBadNormals;
      }
      g_.addFace(t, a);
    }
  }

  // The mesh's vertex colours (its first set), one per vertex once any mesh has them: white for meshes without.
  void colors(const aiMesh& m, std::size_t base) {
    const bool has = m.HasVertexColors(0);
    if (!has && g_.vertexColors.empty()) return;
    g_.vertexColors.resize(base, Color(1.0f));
    auto channel = [](float c) { return std::isfinite(c) ? std::clamp(c, 0.0f, 1.0f) : 1.0f; };
    for (unsigned i = 0; i < m.mNumVertices; ++i) {
      const aiColor4D c = has ? m.mColors[0][i] : aiColor4D(1.0f, 1.0f, 1.0f, 1.0f);
      g_.vertexColors.emplace_back(channel(c.r), channel(c.g), channel(c.b));
    }
  }

  // The mesh's normals in world space (inverse transpose); -1 when it has none. One of no length or not finite is
  // marked in badNormal_ (and stored as +z, never used).
  std::int32_t normals(const aiMesh& m, const aiMatrix4x4& world) {
    badNormal_.assign(m.mNumVertices, false);
    if (!m.mNormals) return -1;
    aiMatrix3x3 toWorld(world);
    toWorld.Inverse().Transpose();
    const std::size_t base = g_.normals.size();
    for (unsigned i = 0; i < m.mNumVertices; ++i) {
      aiVector3D n = toWorld * m.mNormals[i];
      const float length = n.Length();
      badNormal_[i] = !(length > 0.0f) || !std::isfinite(length);
      if (badNormal_[i]) g_.normals.emplace_back(0.0f, 0.0f, 1.0f);
      else g_.normals.emplace_back(n.x / length, n.y / length, n.z / length);
    }
    return static_cast<std::int32_t>(base);
  }

  std::int32_t texCoords(const aiMesh& m) {
    if (!m.mTextureCoords[0] || m.mNumUVComponents[0] < 2) return -1;
    const std::size_t base = g_.texCoords.size();
    for (unsigned i = 0; i < m.mNumVertices; ++i) {
      const aiVector3D& uv = m.mTextureCoords[0][i];
      g_.texCoords.emplace_back(std::isfinite(uv.x) ? uv.x : 0.0f, std::isfinite(uv.y) ? uv.y : 0.0f);
    }
    return static_cast<std::int32_t>(base);
  }

  const aiScene& scene_;
  const fs::path& path_;
  SceneGeometry& g_;
  MeshCounts counts_;
  std::vector<bool> badNormal_;  // of the mesh being gathered, by vertex
};

}  // namespace

void fail(const std::filesystem::path& path, const std::string& message) {
  throwSceneError(SourceLocation{path.string(), 0}, message);
}

Bounds boundsOf(const SceneArray<glm::dvec3>& vertices) {
  Bounds b;
  for (const glm::dvec3& v : vertices) {
    b.lo = b.empty ? v : glm::min(b.lo, v);
    b.hi = b.empty ? v : glm::max(b.hi, v);
    b.empty = false;
  }
  return b;
}

void gatherGeometry(const aiScene& scene, const fs::path& path, SceneGeometry& geometry, Notes& notes) {
  if (!scene.mRootNode) fail(path, "the file has no scene (no root node)");
  Gatherer gatherer(scene, path, geometry);
  // An explicit stack: a deep node tree in a malicious file cannot overflow ours.
  std::vector<std::pair<const aiNode*, aiMatrix4x4>> stack{{scene.mRootNode, scene.mRootNode->mTransformation}};
  std::size_t visited = 0;
  while (!stack.empty()) {
    auto [node, world] = stack.back();
    stack.pop_back();
    if (++visited > 10'000'000) fail(path, "the node tree is too large (a cycle?)");
    gatherer.node(*node, world);
    for (unsigned i = node->mNumChildren; i-- > 0;)
      if (node->mChildren && node->mChildren[i])
        stack.emplace_back(node->mChildren[i], world * node->mChildren[i]->mTransformation);
  }
  if (geometry.triangles.empty()) fail(path, "the file has no triangles (no faces of 3 or more vertices)");
  if (gatherer.counts().pointsAndLines > 0)
    notes.dropped.push_back(std::to_string(gatherer.counts().pointsAndLines) + " points and lines");
  if (gatherer.counts().trianglesWithBadNormals > 0)
    notes.dropped.push_back("the normals of " + std::to_string(gatherer.counts().trianglesWithBadNormals) +
                            " triangles (a normal of zero length or not finite)");
}

}  // namespace rayview::model
