#include "support/scene_compare.h"

#include <gtest/gtest.h>

#include "rayview/scene_codec.h"

namespace rayview::testing {

void expectSameGeometry(const SceneGeometry& a, const SceneGeometry& b) {
  ASSERT_EQ(a.vertices.size(), b.vertices.size());
  for (std::size_t i = 0; i < a.vertices.size(); ++i) ASSERT_EQ(a.vertices[i], b.vertices[i]) << "vertex " << i;
  ASSERT_EQ(a.texCoords.size(), b.texCoords.size());
  for (std::size_t i = 0; i < a.texCoords.size(); ++i) ASSERT_EQ(a.texCoords[i], b.texCoords[i]) << "texcoord " << i;
  ASSERT_EQ(a.normals.size(), b.normals.size());
  for (std::size_t i = 0; i < a.normals.size(); ++i) ASSERT_EQ(a.normals[i], b.normals[i]) << "normal " << i;

  ASSERT_EQ(a.meshes.size(), b.meshes.size());
  for (std::size_t i = 0; i < a.meshes.size(); ++i) {
    EXPECT_EQ(a.meshes[i].id, b.meshes[i].id);
    EXPECT_EQ(a.meshes[i].material, b.meshes[i].material);
    EXPECT_EQ(a.meshes[i].firstTriangle, b.meshes[i].firstTriangle);
    EXPECT_EQ(a.meshes[i].triangleCount, b.meshes[i].triangleCount);
  }
  ASSERT_EQ(a.triangles.size(), b.triangles.size());
  for (std::size_t i = 0; i < a.triangles.size(); ++i) {
    const Triangle &ta = a.triangles[i], &tb = b.triangles[i];
    const FaceAttributes &fa = a.attributesOf(i), &fb = b.attributesOf(i);
    for (int k = 0; k < 3; ++k) {
      ASSERT_EQ(ta.vertex[k], tb.vertex[k]) << "triangle " << i;
      ASSERT_EQ(fa.texCoord[k], fb.texCoord[k]) << "triangle " << i;
      ASSERT_EQ(fa.normal[k], fb.normal[k]) << "triangle " << i;
    }
  }

  ASSERT_EQ(a.texture.has_value(), b.texture.has_value());
  if (a.texture) {
    EXPECT_EQ(a.texture->width, b.texture->width);
    EXPECT_EQ(a.texture->height, b.texture->height);
    EXPECT_TRUE(a.texture->rgb == b.texture->rgb);
  }
  // The materials' own images, in order; their names may differ (a file written elsewhere names them from there).
  ASSERT_EQ(a.materialTextures.size(), b.materialTextures.size());
  for (std::size_t i = 0; i < a.materialTextures.size(); ++i)
    EXPECT_TRUE(a.materialTextures[i].image == b.materialTextures[i].image) << a.materialTextures[i].name;
}

Scene throughTheCodec(const Scene& scene) {
  Bytes bytes;
  encodeParameters(scene.parameters(), bytes);
  encodeGeometry(scene.geometry(), bytes);
  std::size_t at = 0;
  Scene out;
  out.parameters() = decodeParameters(bytes.data(), bytes.size(), at);
  static_cast<SceneGeometry&>(out) = decodeGeometry(bytes.data(), bytes.size(), at);
  EXPECT_EQ(at, bytes.size());
  return out;
}

}  // namespace rayview::testing
