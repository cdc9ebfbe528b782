// rayview's own model readers (import/obj_reader.h, the PLY and STL readers) on small models each test writes:
// exact numbers and shared vertices, meshes per group and material, every bad index refused with its line, what
// is dropped said in the summary. Read in this process (rayview/model_import.h), as the import worker reads them.

#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <random>
#include <sstream>
#include <string>

#include "rayview/diagnostics.h"
#include "rayview/model_import.h"
#include "rayview/scene_loader.h"
#include "rayview/scene_writer.h"
#include "support/image_compare.h"

namespace rayview {
namespace {

namespace fs = std::filesystem;

fs::path writeFile(const std::string& name, const std::string& bytes) {
  const fs::path dir = testing::testOutputDirectory() / "model_readers";
  fs::create_directories(dir);
  std::ofstream(dir / name, std::ios::binary) << bytes;
  return dir / name;
}

ModelScene read(const fs::path& path) { return readModel(path, ModelImportOptions{}); }

// The refusal's message and line, or "" when the file was read.
std::pair<std::string, int> refusal(const std::string& name, const std::string& text) {
  const fs::path path = writeFile(name, text);
  try {
    read(path);
  } catch (const SceneError& error) {
    EXPECT_EQ(error.diagnostic().where.file, path.string());
    return {error.diagnostic().message, error.diagnostic().where.line};
  }
  return {"", 0};
}

const std::string kSquare = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n";

TEST(ObjReader, NumbersAreExactAndVerticesStayShared) {
  std::mt19937_64 random(11);
  std::uniform_real_distribution<double> coordinate(-1000.0, 1000.0);
  std::ostringstream obj;
  std::vector<double> written;
  char buffer[64];
  for (int i = 0; i < 300; ++i)
    for (int c = 0; c < 3; ++c) {
      written.push_back(coordinate(random) * (c == 1 ? 1e-4 : 1.0));
      std::snprintf(buffer, sizeof buffer, "%.17g", written.back());
      obj << (c == 0 ? "v " : " ") << buffer << (c == 2 ? "\n" : "");
    }
  for (int i = 1; i + 2 <= 300; ++i) obj << "f " << i << " " << i + 1 << " " << i + 2 << "\n";  // each vertex in 3 faces
  const Scene scene = read(writeFile("exact.obj", obj.str())).scene;
  ASSERT_EQ(scene.vertices.size(), 300u);  // shared, not one per corner
  EXPECT_EQ(scene.triangles.size(), 298u);
  for (std::size_t i = 0; i < 300; ++i)
    for (int c = 0; c < 3; ++c) ASSERT_EQ(scene.vertices[i][c], written[3 * i + c]) << i;
  // Into the scene format: the same doubles. Back to OBJ (written in float, as the exporter writes models): the same
  // floats, bit for bit, and no more vertices.
  const fs::path xml = writeFile("exact.xml", ""), back = writeFile("exact_back.obj", "");
  writeSceneFile(xml, scene);
  const Scene fromXml = loadSceneFile(xml).scene;
  ASSERT_EQ(fromXml.vertices, scene.vertices);
  exportScene(fromXml, back);
  const Scene again = read(back).scene;
  ASSERT_EQ(again.vertices.size(), 300u);
  for (std::size_t i = 0; i < 300; ++i)
    for (int c = 0; c < 3; ++c)
      ASSERT_EQ(static_cast<float>(again.vertices[i][c]), static_cast<float>(scene.vertices[i][c])) << i;
}

TEST(ObjReader, GroupsAndMaterialsAreMeshesAndPolygonsFans) {
  writeFile("two.mtl", "newmtl red\nKd 0.9 0.1 0.1\nKs 0.4 0.4 0.4\nNs 60\nnewmtl blue\nKd 0.1 0.1 0.9\n");
  const ModelScene model = read(writeFile("groups.obj", "mtllib two.mtl\n" + kSquare +
                                                            "g first\nusemtl red\nf 1 2 3 4\ng second\nf -4 -3 -2\n"
                                                            "usemtl blue\nf 1 3 4\nusemtl nowhere\nf 2 3 4\n"));
  const Scene& scene = model.scene;
  ASSERT_EQ(scene.meshes.size(), 4u);
  EXPECT_EQ(scene.meshes[0].id, "first");
  EXPECT_EQ(scene.meshes[0].triangleCount, 2u);  // the quad as a fan
  EXPECT_EQ(scene.triangles[1].vertex[1], 2u);
  EXPECT_EQ(scene.triangles[1].vertex[2], 3u);
  EXPECT_EQ(scene.meshes[1].id, "second");
  EXPECT_EQ(scene.meshes[2].id, "second_2");
  ASSERT_EQ(scene.materials.size(), 3u);
  EXPECT_EQ(scene.materials[scene.meshes[0].material].id, "red");
  EXPECT_FLOAT_EQ(scene.materials[0].phongExponent, 60.0f);
  EXPECT_EQ(scene.meshes[1].material, scene.meshes[0].material);
  EXPECT_EQ(scene.materials[scene.meshes[2].material].id, "blue");
  EXPECT_FLOAT_EQ(scene.materials[scene.meshes[2].material].diffuse.z, 0.9f);
  EXPECT_EQ(scene.materials[scene.meshes[3].material].id, "nowhere");
  ASSERT_EQ(model.warnings.size(), 1u);
  EXPECT_NE(model.warnings[0].find("\"nowhere\""), std::string::npos);
}

// A usemtl before the mtllib line that defines its material still gets the definition.
TEST(ObjReader, AMaterialLibraryAfterItsUsemtlStillDefinesIt) {
  writeFile("late.mtl", "newmtl late\nKd 0.2 0.3 0.4\n");
  const Scene scene = read(writeFile("late.obj", kSquare + "usemtl late\nf 1 2 3\nmtllib late.mtl\n")).scene;
  ASSERT_EQ(scene.materials.size(), 1u);
  EXPECT_FLOAT_EQ(scene.materials[0].diffuse.z, 0.4f);
}

TEST(ObjReader, EveryOutOfRangeIndexIsRefusedWithItsLine) {
  const std::string uv = "vt 0 0\n", n = "vn 0 0 1\n";
  const struct {
    std::string text, says;
    int line;
  } cases[] = {
      {kSquare + "f 1 2 9\n", "vertex 9", 5},
      {kSquare + uv + "f 1/99 2/1 3/1\n", "texture coordinate 99", 6},
      {kSquare + n + "f 1//1 2//2 3//1\n", "normal 2", 6},
      {kSquare + "f 1 2 -5\n", "vertex -5", 5},
      {kSquare + uv + "f 1/1 2/-2 3/1\n", "texture coordinate -2", 6},
      {kSquare + "f 0 1 2\n", "vertex 0", 5},
      {kSquare + "f 1 2 x\n", "expected a vertex index", 5},
      {"v 0 0\n", "expected a vertex coordinate", 1},
  };
  for (const auto& c : cases) {
    const auto [message, line] = refusal("bad.obj", c.text);
    EXPECT_NE(message.find(c.says), std::string::npos) << c.text << " -> " << message;
    EXPECT_EQ(line, c.line) << c.text;
  }
  // A vertex defined after the face that names it is not out of range (Assimp reads such files too).
  EXPECT_EQ(read(writeFile("later.obj", "f 1 2 3\n" + kSquare)).scene.triangles.size(), 1u);
}

TEST(ObjReader, AZeroNormalLeavesOutOnlyItsFacesNormals) {
  const ModelScene model = read(writeFile("zero.obj", kSquare + "vn 0 0 1\nvn 0 0 0\ng a\nf 1//1 2//1 3//1\n"
                                                                "f 1//2 3//1 4//1\ng b\nf 1//1 3//1 4//1\n"));
  const Scene& scene = model.scene;
  ASSERT_EQ(scene.triangles.size(), 3u);
  EXPECT_TRUE(scene.attributesOf(0).hasNormals());
  EXPECT_FALSE(scene.attributesOf(1).hasNormals());
  EXPECT_TRUE(scene.attributesOf(2).hasNormals());
  EXPECT_NE(model.summary.find("dropped: the normals of 1 triangles"), std::string::npos) << model.summary;
}

TEST(ObjReader, ManyGroupsAndMaterialsOpenQuickly) {
  std::ostringstream obj, mtl;
  obj << "mtllib many.mtl\n";
  for (int i = 0; i < 20000; ++i) {
    mtl << "newmtl m" << i << "\nKd 0.5 0.5 0.5\n";
    obj << "v " << i << " 0 0\nv " << i << " 1 0\nv " << i << " 0 1\no part" << i << "\nusemtl m" << i << "\nf -3 -2 -1\n";
  }
  writeFile("many.mtl", mtl.str());
  const Scene scene = read(writeFile("many.obj", obj.str())).scene;
  EXPECT_EQ(scene.meshes.size(), 20000u);
  EXPECT_EQ(scene.materials.size(), 20000u);
}

TEST(OwnReaders, AsciiStlKeepsEverySolid) {
  const std::string facet = "facet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\n";
  const Scene scene = read(writeFile("two.stl", "solid a\n" + facet + "endsolid a\nsolid b\n" + facet + facet +
                                                    "endsolid b\n"))
                          .scene;
  EXPECT_EQ(scene.triangles.size(), 3u);
  ASSERT_EQ(scene.meshes.size(), 2u);
  EXPECT_EQ(scene.meshes[1].id, "b");
  EXPECT_EQ(scene.meshes[1].triangleCount, 2u);
}

TEST(OwnReaders, PlyColoursAreKeptAndStripsRead) {
  const ModelScene model = read(writeFile(
      "strips.ply", "ply\nformat ascii 1.0\ncomment Created by Blender\nobj_info made here\nelement vertex 4\n"
                    "property float x\nproperty float y\nproperty float z\nproperty uchar red\nproperty uchar green\n"
                    "property uchar blue\nelement tristrips 1\nproperty list int int vertex_indices\nend_header\n"
                    "0 0 0 255 0 0\n1 0 0 0 255 0\n0 1 0 0 0 255\n1 1 0 9 9 9\n4 0 1 2 3\n"));
  EXPECT_EQ(model.scene.triangles.size(), 2u);
  EXPECT_NE(model.summary.find("dropped: nothing"), std::string::npos) << model.summary;
  ASSERT_EQ(model.scene.vertexColors.size(), 4u);
  EXPECT_EQ(model.scene.vertexColors[1], Color(0.0f, 1.0f, 0.0f));
}

// A TGA texture named by map_Kd (with an option before the file name) is read and kept, under the name of the copy
// `import` saves beside the scene: the model's name, numbered from the second texture on.
TEST(ObjReader, TgaTextureFromTheMtlIsKept) {
  std::string tga(18, '\0');
  tga[2] = 2, tga[12] = 2, tga[14] = 2, tga[16] = 24;
  writeFile("wood.tga", tga + std::string(12, '\x40'));
  writeFile("stone.tga", tga + std::string(12, '\x80'));
  writeFile("textured.mtl", "newmtl wood\nKd 1 1 1\nmap_Kd -s 1 1 1 wood.tga\nnewmtl stone\nmap_Kd stone.tga\n");
  const ModelScene model =
      read(writeFile("textured.obj", "mtllib textured.mtl\n" + kSquare +
                                         "vt 0 0\nvt 1 0\nvt 1 1\nusemtl wood\nf 1/1 2/2 3/3\nusemtl stone\nf 1/1 3/3 4/2\n"));
  EXPECT_NE(model.summary.find("textures wood.tga (2x2), stone.tga (2x2)"), std::string::npos) << model.summary;
  ASSERT_EQ(model.scene.materials.size(), 2u);
  EXPECT_EQ(model.scene.materials[0].id, "wood");
  const Texture* texture = model.scene.textureOf(model.scene.materials[0]);
  ASSERT_TRUE(texture);
  EXPECT_EQ(texture->rgb[0], 0x40);
  EXPECT_EQ(model.scene.materials[0].textureImage, "textured_texture.png");
  EXPECT_EQ(model.scene.materials[1].textureImage, "textured_texture-2.png");
  ASSERT_TRUE(model.scene.textureOf(model.scene.materials[1]));
  EXPECT_EQ(model.scene.textureOf(model.scene.materials[1])->rgb[0], 0x80);
}

// An opacity map (map_d, a grey image) is the material's cut-out at cutoff 0.5.
TEST(ObjReader, AnOpacityMapIsACutOut) {
  writeFile("mask.pgm", std::string("P5\n2 1\n255\n") + '\0' + '\xff');
  writeFile("leaf.mtl", "newmtl leaf\nKd 0.2 0.8 0.2\nmap_d mask.pgm\n");
  const ModelScene model = read(writeFile("leaf.obj", "mtllib leaf.mtl\n" + kSquare +
                                                          "vt 0 0\nvt 1 0\nvt 1 1\nusemtl leaf\nf 1/1 2/2 3/3\n"));
  const Material& m = model.scene.materials.at(0);
  ASSERT_FALSE(m.alphaImage.empty()) << model.summary;
  EXPECT_EQ(m.alphaCutoff, 0.5f);
  const Texture* mask = model.scene.textureNamed(m.alphaImage);
  ASSERT_TRUE(mask);
  EXPECT_EQ(mask->rgb, (PixelBytes{0, 0, 0, 255, 255, 255}));
}

}  // namespace
}  // namespace rayview
