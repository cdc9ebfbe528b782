// What the viewer's workers receive under MPI (cluster/view_codec.h): the geometry and each edit's parameters come
// back exactly, and malformed bytes are refused, never misread.
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>

#include "rayview/scene_loader.h"
#include "scene_hash.h"
#include "view_codec.h"

namespace rayview::cluster {
namespace {

// Point and triangular lights, a texture, texture coordinates and vertex normals.
Scene texturedScene() {
  const std::filesystem::path path = std::filesystem::path(RAYVIEW_SOURCE_DIR) / "scenes" / "textured_2025.xml";
  LoadedScene loaded = loadSceneFile(path);
  EXPECT_TRUE(loaded.scene.texture.has_value());
  EXPECT_FALSE(loaded.scene.normals.empty());
  return std::move(loaded.scene);
}

// Values an edit makes (an orbit's camera, a slider's colour), not the tidy decimals of a file.
SceneParameters edited(SceneParameters p) {
  p.camera.position = {0.1 + 1e-17, -2.0 / 3.0, 1e-300};
  p.camera.left = -0.7000000000000001;
  p.camera.width = 321;
  p.shadowRayEpsilon = 1e-5;
  p.maxRayDepth = 7;
  p.materials.at(0).diffuse = Color(0.1f, 1.0f / 3.0f, 0.99999994f);
  p.materials.at(0).id = "edited \"material\"";
  p.materials.at(0).twoSided = true;  // an imported model's material
  p.lights.of<PointLight>().at(0).position = {1.0 / 7.0, 2.0, -3.5};
  return p;
}

TEST(ViewCodec, ASnapshotComesBackExactly) {
  const Scene scene = texturedScene();
  RenderSettings settings;
  settings.pixelSamples = 4;
  settings.lightSamples = 9;
  settings.triangularLightModel = TriangularLightModel::Directional;
  settings.accel = AccelKind::Reference;
  for (const SceneParameters& p : {scene.parameters(), edited(scene.parameters())}) {
    const Bytes bytes = encodeSnapshot(p, settings);
    const Snapshot back = decodeSnapshot(bytes.data(), bytes.size());
    EXPECT_TRUE(back.parameters == p);
    EXPECT_TRUE(back.settings == settings);
  }
}

TEST(ViewCodec, TheGeometryComesBackExactly) {
  const Scene scene = texturedScene();
  const glm::dvec3 origin{1.5, -2.25, 1e9};
  const Bytes bytes = encodeGeometry(scene.geometry(), origin, AccelKind::Packet);
  const ShippedGeometry back = decodeGeometry(bytes.data(), bytes.size());
  EXPECT_EQ(back.origin, origin);
  EXPECT_EQ(back.accel, AccelKind::Packet);
  Scene rebuilt;
  rebuilt.parameters() = scene.parameters();
  static_cast<SceneGeometry&>(rebuilt) = *back.geometry;
  EXPECT_EQ(sceneHash(rebuilt), sceneHash(scene)) << "every array, mesh and the texture";
  EXPECT_EQ(back.geometry->textureImage, scene.textureImage);
  EXPECT_FALSE(back.parameters.has_value());
  // With the parameters, as the viewer sends its workers the materials their cut-outs come from.
  Scene withCutOut = scene;
  withCutOut.materials.at(0).alphaImage = "leaf.png";
  withCutOut.materials.at(0).alphaCutoff = 0.25f;
  const Bytes both = encodeGeometry(withCutOut.geometry(), origin, AccelKind::Packet, &withCutOut.parameters());
  const ShippedGeometry again = decodeGeometry(both.data(), both.size());
  ASSERT_TRUE(again.parameters.has_value());
  EXPECT_EQ(*again.parameters, withCutOut.parameters());
}

TEST(ViewCodec, TruncatedOrTamperedBytesAreRefused) {
  const Scene scene = texturedScene();
  const Bytes snapshot = encodeSnapshot(edited(scene.parameters()), RenderSettings{});
  for (std::size_t size = 0; size < snapshot.size(); ++size)
    EXPECT_THROW(decodeSnapshot(snapshot.data(), size), CodecError) << size;
  const Bytes geometry = encodeGeometry(scene.geometry(), {}, AccelKind::Embree);
  for (std::size_t size = 0; size < geometry.size(); size += 1 + size / 8)
    EXPECT_THROW(decodeGeometry(geometry.data(), size), CodecError) << size;
  // A bit flipped in a number (here the lowest of the camera's x, just past the header and settings) is caught by
  // the parameters' hash, the check a worker makes of every snapshot.
  Bytes flipped = snapshot;
  const std::size_t cameraX = 4 + 8 + sizeof(RenderSettings) + sizeof(int) + sizeof(Color) + 1 + 8;
  flipped.at(cameraX) ^= 1;
  EXPECT_THROW(decodeSnapshot(flipped.data(), flipped.size()), CodecError);
  // A huge count never allocates.
  Bytes huge = geometry;
  const std::uint64_t count = ~std::uint64_t{0} / 2;
  std::memcpy(huge.data() + 4 + sizeof(glm::dvec3) + sizeof(AccelKind), &count, sizeof count);
  EXPECT_THROW(decodeGeometry(huge.data(), huge.size()), CodecError);
}

}  // namespace
}  // namespace rayview::cluster
