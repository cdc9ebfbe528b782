// The plain PLY reader (renderer/ply_reader.h) on PLY files the test writes itself: ASCII, binary little- and
// big-endian, extra properties and elements skipped, polygons split into fans, and every refusal.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <bit>
#include <limits>
#include <cstring>
#include <string>
#include <vector>

#include "rayview/ply_reader.h"

namespace rayview {
namespace {

using detail::parsePly;
using detail::PlyError;
using detail::PlyMesh;

enum class Format { Ascii, Little, Big };

// Four vertices (x y z, then a normal and a colour this reader skips), a quad, a triangle and a two-vertex face,
// and an "edge" element after the faces.
struct PlyWriter {
  Format format;
  std::string out;

  template <class T>
  void put(T v) {
    if (format == Format::Ascii) {
      out += std::to_string(v) + " ";
      return;
    }
    unsigned char b[sizeof(T)];
    std::memcpy(b, &v, sizeof(T));
    if ((format == Format::Big) == (std::endian::native == std::endian::little)) std::reverse(b, b + sizeof(T));
    out.append(reinterpret_cast<const char*>(b), sizeof(T));
  }
  void endRecord() {
    if (format == Format::Ascii) out += "\n";
  }
};

const float kVertices[4][3] = {{-1, -1, -2}, {1, -1, -2}, {1, 1, -2}, {-1, 1, -2.5f}};

std::string samplePly(Format format, int vertexCount = 4) {
  const char* name = format == Format::Ascii ? "ascii" : format == Format::Little ? "binary_little_endian" : "binary_big_endian";
  PlyWriter w{format, "ply\nformat " + std::string(name) + " 1.0\ncomment made by the test\n"};
  w.out += "element vertex " + std::to_string(vertexCount) + "\nproperty float x\nproperty float y\nproperty float z\n"
           "property float nx\nproperty uchar red\nelement face 3\nproperty list uchar int vertex_indices\n"
           "element edge 1\nproperty int vertex1\nproperty int vertex2\nend_header\n";
  for (int i = 0; i < vertexCount; ++i) {
    for (float c : kVertices[i % 4]) w.put(c);
    w.put(0.5f);
    w.put(static_cast<unsigned char>(200));
    w.endRecord();
  }
  const std::vector<std::vector<int>> faces = {{0, 1, 2, 3}, {3, 2, 1}, {0, 1}};
  for (const auto& f : faces) {
    w.put(static_cast<unsigned char>(f.size()));
    for (int i : f) w.put(i);
    w.endRecord();
  }
  w.put(0);
  w.put(1);
  w.endRecord();
  return w.out;
}

std::string errorOf(const std::string& bytes) {
  try {
    parsePly(bytes);
  } catch (const PlyError& e) {
    return e.message;
  }
  ADD_FAILURE() << "the PLY was read";
  return "";
}

std::array<std::uint32_t, 3> corners(const Triangle& t) { return {t.vertex[0], t.vertex[1], t.vertex[2]}; }

class PlyFormats : public ::testing::TestWithParam<Format> {};

TEST_P(PlyFormats, ReadsVerticesAndFansOfEveryFace) {
  const PlyMesh mesh = parsePly(samplePly(GetParam()));
  ASSERT_EQ(mesh.vertices.size(), 4u);
  for (int i = 0; i < 4; ++i)
    EXPECT_EQ(mesh.vertices[i], glm::dvec3(kVertices[i][0], kVertices[i][1], kVertices[i][2])) << i;
  ASSERT_EQ(mesh.triangles.size(), 3u);  // the quad as two, then the triangle
  EXPECT_EQ(corners(mesh.triangles[0]), (std::array<std::uint32_t, 3>{0, 1, 2}));
  EXPECT_EQ(corners(mesh.triangles[1]), (std::array<std::uint32_t, 3>{0, 2, 3}));
  EXPECT_EQ(corners(mesh.triangles[2]), (std::array<std::uint32_t, 3>{3, 2, 1}));
  EXPECT_EQ(mesh.skippedFaces, 1u);
  EXPECT_TRUE(mesh.normals.empty());  // nx alone is no normal
  EXPECT_TRUE(mesh.texCoords.empty());
}

// Normals and texture coordinates (named s and t here) come one per vertex, as the file gives them.
TEST_P(PlyFormats, ReadsNormalsAndTextureCoordinates) {
  const char* name = GetParam() == Format::Ascii ? "ascii" : GetParam() == Format::Little ? "binary_little_endian" : "binary_big_endian";
  PlyWriter w{GetParam(), "ply\nformat " + std::string(name) + " 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                          "property float z\nproperty float s\nproperty double nx\nproperty float ny\nproperty float nz\n"
                          "property float t\nelement face 1\nproperty list uchar uint vertex_indices\nend_header\n"};
  for (int i = 0; i < 3; ++i) {
    for (float c : kVertices[i]) w.put(c);
    w.put(0.25f * static_cast<float>(i));
    w.put(0.0);
    w.put(0.0f);
    w.put(2.0f);
    w.put(0.5f);
    w.endRecord();
  }
  w.put(static_cast<unsigned char>(3));
  for (std::uint32_t i : {2u, 1u, 0u}) w.put(i);
  const PlyMesh mesh = parsePly(w.out);
  ASSERT_EQ(mesh.normals.size(), 3u);
  ASSERT_EQ(mesh.texCoords.size(), 3u);
  EXPECT_EQ(mesh.normals[1], glm::vec3(0, 0, 2));  // not normalized: the caller decides
  EXPECT_EQ(mesh.texCoords[2], glm::vec2(0.5f, 0.5f));
  ASSERT_EQ(mesh.triangles.size(), 1u);
  EXPECT_EQ(corners(mesh.triangles[0]), (std::array<std::uint32_t, 3>{2, 1, 0}));
}

TEST_P(PlyFormats, RefusesATruncatedFile) {
  const std::string whole = samplePly(GetParam());
  // Cut inside the faces: the edge element's 2 values and the last face are gone.
  const std::string cut = whole.substr(0, whole.size() - (GetParam() == Format::Ascii ? 12 : 20));
  EXPECT_NE(errorOf(cut).find("truncated"), std::string::npos) << errorOf(cut);
}

TEST_P(PlyFormats, RefusesACountTheFileCannotHold) {
  std::string bytes = samplePly(GetParam());
  bytes.replace(bytes.find("element vertex 4"), 16, "element vertex 400000000");
  EXPECT_NE(errorOf(bytes).find("more than the"), std::string::npos) << errorOf(bytes);
}

INSTANTIATE_TEST_SUITE_P(Ply, PlyFormats, ::testing::Values(Format::Ascii, Format::Little, Format::Big),
                         [](const auto& info) {
                           return std::string(info.param == Format::Ascii    ? "Ascii"
                                              : info.param == Format::Little ? "BinaryLittleEndian"
                                                                              : "BinaryBigEndian");
                         });

const std::string kAsciiHead = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                               "element face 1\nproperty list uchar int vertex_indices\nend_header\n";

TEST(Ply, AcceptsCrlfLinesAndDoubleCoordinates) {
  const PlyMesh mesh = parsePly("ply\r\nformat ascii 1.0\r\nelement vertex 3\r\nproperty double x\r\nproperty double y\r\n"
                                "property double z\r\nelement face 1\r\nproperty list uchar uint vertex_index\r\n"
                                "end_header\r\n0 0 0\r\n1 0 0\r\n0 1 0.125\r\n3 0 1 2\r\n");
  ASSERT_EQ(mesh.triangles.size(), 1u);
  EXPECT_EQ(mesh.vertices[2], glm::dvec3(0, 1, 0.125));
}

TEST(Ply, AcceptsBlankLinesBeforeTheMagicWord) {
  const PlyMesh mesh = parsePly("\n \r\n" + kAsciiHead + "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
  EXPECT_EQ(mesh.triangles.size(), 1u);
  EXPECT_NE(errorOf("\n" + kAsciiHead + "0 0 0\n1 0 0\nx 1 0\n3 0 1 2\n").find("line 13: expected a number"), std::string::npos);
}

TEST(Ply, RefusesWhatIsNotAReadableMesh) {
  EXPECT_NE(errorOf("solid cube\n").find("not a PLY file"), std::string::npos);
  EXPECT_NE(errorOf("ply\nformat ascii 1.0\nelement vertex 0\n").find("no end_header"), std::string::npos);
  EXPECT_NE(errorOf("ply\nformat binary_middle_endian 1.0\nend_header\n").find("line 2: unknown format"), std::string::npos);
  EXPECT_NE(errorOf("ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nelement face 0\n"
                    "property list uchar int vertex_indices\nend_header\n0 0\n")
                .find("line 3: the vertex element has no x, y and z"),
            std::string::npos);
  EXPECT_NE(errorOf("ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\n"
                    "end_header\n0 0 0\n")
                .find("no face element"),
            std::string::npos);
  EXPECT_NE(errorOf("ply\nformat ascii 1.0\nelement vertex 1\nproperty quad x\nend_header\n").find("line 4: unknown property type 'quad'"),
            std::string::npos);
}

TEST(Ply, RefusesBadValuesWithTheirLine) {
  EXPECT_NE(errorOf(kAsciiHead + "0 0 0\n1 0 0\nnan 1 0\n3 0 1 2\n").find("line 12: expected a number"), std::string::npos)
      << errorOf(kAsciiHead + "0 0 0\n1 0 0\nnan 1 0\n3 0 1 2\n");
  EXPECT_NE(errorOf(kAsciiHead + "0 0 0\n1 0 0\n0 1 0\n3 0 1 9\n").find("line 13: face 0 uses vertex 9, but the file has 3 vertices"),
            std::string::npos);
  EXPECT_NE(errorOf(kAsciiHead + "0 0 0\n1 0 0\n0 1 0\n3 0 -1 2\n").find("uses vertex -1"), std::string::npos);
  EXPECT_NE(errorOf(kAsciiHead + "0 0 0\n1 0 0\n0 1 0\n3 0 1.5 2\n").find("expected an integer"), std::string::npos);
  EXPECT_NE(errorOf(kAsciiHead + "0 0 0\n1 0 0\n0 1 0\n200 0 1 2\n").find("more than the rest of the file holds"),
            std::string::npos);
}

TEST(Ply, RefusesNonFiniteBinaryCoordinates) {
  std::string bytes = samplePly(Format::Little);
  const float inf = std::numeric_limits<float>::infinity();
  const std::size_t body = bytes.find("end_header\n") + 11;
  std::memcpy(bytes.data() + body + 4, &inf, 4);  // vertex 0's y
  EXPECT_NE(errorOf(bytes).find("vertex 0 has a coordinate that is not a finite number"), std::string::npos) << errorOf(bytes);
}

// Header lines other tools write and Assimp and VTK pass over: Blender's "Created by" line, obj_info, comments.
TEST(Ply, PassesOverHeaderLinesThatSayNothingAboutTheRecords) {
  const PlyMesh mesh = parsePly("ply\nformat ascii 1.0\nCreated by Blender 2.79\ncomment made here\nobj_info num_cols 3\n" +
                                kAsciiHead.substr(kAsciiHead.find("element")) + "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
  EXPECT_EQ(mesh.triangles.size(), 1u);
}

// Each ASCII record is a line: values past the properties (as some writers leave) do not shift the next records.
TEST(Ply, PassesOverExtraValuesAtTheEndOfAnAsciiRecord) {
  const PlyMesh mesh = parsePly(kAsciiHead + "0 0 0 9 9\n1 0 0\n0 1 0.5 7\n3 0 1 2 0\n");
  ASSERT_EQ(mesh.triangles.size(), 1u);
  EXPECT_EQ(mesh.vertices[2], glm::dvec3(0, 1, 0.5));
  EXPECT_EQ(mesh.triangles[0].vertex[2], 2u);
}

// Triangle strips (-1 restarts a strip) become triangles that keep the strip's winding.
TEST(Ply, ReadsTriangleStripsWithRestarts) {
  const std::string head = "ply\nformat ascii 1.0\nelement vertex 5\nproperty float x\nproperty float y\nproperty float z\n"
                           "element tristrips 1\nproperty list int int vertex_indices\nend_header\n";
  const PlyMesh mesh = parsePly(head + "0 0 0\n1 0 0\n0 1 0\n1 1 0\n2 2 0\n8 0 1 2 3 -1 1 3 4\n");
  ASSERT_EQ(mesh.triangles.size(), 3u);
  const std::uint32_t expected[3][3] = {{0, 1, 2}, {2, 1, 3}, {1, 3, 4}};
  for (int t = 0; t < 3; ++t)
    for (int k = 0; k < 3; ++k) EXPECT_EQ(mesh.triangles[t].vertex[k], expected[t][k]) << t << " " << k;
  EXPECT_NE(errorOf(head + "0 0 0\n1 0 0\n0 1 0\n1 1 0\n2 2 0\n4 0 1 2 5\n").find("uses vertex 5"), std::string::npos);
}

// Colours, as bytes or as floats, are read in 0..1.
TEST(Ply, ReadsVertexColours) {
  const std::string head = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                           "property uchar red\nproperty uchar green\nproperty uchar blue\nproperty uchar alpha\n"
                           "element face 1\nproperty list uchar int vertex_indices\nend_header\n";
  const PlyMesh mesh = parsePly(head + "0 0 0 255 0 0 255\n1 0 0 0 255 0 255\n0 1 0 0 0 51 255\n3 0 1 2\n");
  ASSERT_EQ(mesh.colors.size(), 3u);
  EXPECT_EQ(mesh.colors[0], glm::vec3(1, 0, 0));
  EXPECT_FLOAT_EQ(mesh.colors[2].z, 0.2f);
}

}  // namespace
}  // namespace rayview
