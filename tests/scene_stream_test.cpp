// The big blocks read as a stream (renderer/scene_loader_internal.h): every scene loads the same with and
// without it (scene, warnings, or the error), and the stream is really taken where it can read exactly.

#include <gtest/gtest.h>

#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "rayview/scene_loader.h"
#include "scene_loader_internal.h"
#include "support/image_compare.h"
#include "support/loader_scenes.h"
#include "support/scene_compare.h"

namespace rayview {
namespace {

namespace fs = std::filesystem;
using loader_testing::kBase;
using loader_testing::with;

struct Outcome {
  bool ok = false;
  std::string error;
  std::vector<std::string> warnings;
  Scene scene;
};

template <class Load>
Outcome outcomeOf(Load&& load) {
  Outcome out;
  try {
    LoadedScene loaded = load();
    out.ok = true;
    for (const Diagnostic& d : loaded.warnings) out.warnings.push_back(d.format());
    out.scene = std::move(loaded.scene);
  } catch (const SceneError& e) {
    out.error = e.what();
  }
  return out;
}

Outcome loadText(const std::string& xml, bool stream, bool strict = false) {
  LoadOptions options;
  options.streamBlocks = stream;
  options.strict = strict;
  options.loadTexture = false;
  return outcomeOf([&] { return loadSceneText(xml, "s.xml", ".", options); });
}

Outcome loadFile(const fs::path& path, bool stream) {
  LoadOptions options;
  options.streamBlocks = stream;
  return outcomeOf([&] { return loadSceneFile(path, options); });
}

void expectSame(const Outcome& streamed, const Outcome& dom, const std::string& what) {
  SCOPED_TRACE(what);
  ASSERT_EQ(streamed.ok, dom.ok) << streamed.error << " | " << dom.error;
  EXPECT_EQ(streamed.error, dom.error);
  EXPECT_EQ(streamed.warnings, dom.warnings);
  if (!streamed.ok) return;
  EXPECT_TRUE(streamed.scene.parameters() == dom.scene.parameters());
  EXPECT_EQ(streamed.scene.textureImage, dom.scene.textureImage);
  testing::expectSameGeometry(streamed.scene, dom.scene);
}

// Reads `xml` as the stream reads a file; `xml` must outlive it.
scene_loading::ReadAt readerOf(const std::string& xml) {
  return [&xml](std::uint64_t offset, char* into, std::size_t count) -> long {
    if (offset >= xml.size()) return 0;
    const std::size_t n = std::min<std::uint64_t>(count, xml.size() - offset);
    std::memcpy(into, xml.data() + offset, n);
    return static_cast<long>(n);
  };
}

// Does the stream read this text by itself (no fallback to the ordinary reading)?
bool streams(const std::string& xml, bool strict = false, int threads = 1) {
  using namespace scene_loading;
  const ReadAt read = readerOf(xml);
  const std::string name = "s.xml";
  LoadOptions options;
  options.strict = strict;
  options.loadTexture = false;
  try {
    StreamedBlocks streamed = streamSkeleton(read, xml.size());
    Loader::parseStreamedBlocks(streamed, read, threads);
    Loader(name, ".", options).loadStreamed(streamed);
    return true;
  } catch (const StreamAbandoned&) {
    return false;
  } catch (const SceneError&) {
    return false;
  }
}

void expectSameText(const std::string& xml, bool expectStreamed, const std::string& what, bool strict = false) {
  expectSame(loadText(xml, true, strict), loadText(xml, false, strict), what);
  EXPECT_EQ(streams(xml, strict), expectStreamed) << what;
}

// ---------------------------------------------------------------- real files

std::vector<fs::path> sceneFiles() {
  std::vector<fs::path> files;
  for (const fs::path& root : {fs::path(RAYVIEW_SHARED_DIR), fs::path(RAYVIEW_SOURCE_DIR) / "scenes"})
    for (const auto& entry : fs::recursive_directory_iterator(root))
      if (entry.is_regular_file() && entry.path().extension() == ".xml") files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  return files;
}

TEST(SceneStream, EveryRealFileLoadsTheSameEitherWay) {
  RAYVIEW_SKIP_WITHOUT_SHARED();
  const std::vector<fs::path> files = sceneFiles();
  ASSERT_GE(files.size(), 60u);
  for (const fs::path& file : files) expectSame(loadFile(file, true), loadFile(file, false), file.string());
}

TEST(SceneStream, TheConformanceScenesAreStreamed) {
  RAYVIEW_SKIP_WITHOUT_SHARED();
  // They are clean: the stream must read each by itself, or it buys nothing where it matters. So must the course's
  // own files (the CENG477 dialect), but killeroo's, whose <VertexData> holds a comment.
  std::size_t count = 0;
  for (const auto& entry : fs::directory_iterator(fs::path(RAYVIEW_SHARED_DIR) / "conformance" / "ceng477")) {
    const std::string name = entry.path().filename().string();
    if (entry.path().extension() != ".xml") continue;
    ++count;
    std::ifstream in(entry.path(), std::ios::binary);
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    EXPECT_EQ(streams(text), name != "killeroo_2020.ceng477.xml") << entry.path();
  }
  EXPECT_EQ(count, 32u);
}

// ---------------------------------------------------------------- what it reads itself

TEST(SceneStream, TheBaseSceneIsStreamed) { expectSameText(kBase, true, "base"); }

TEST(SceneStream, ZeroBasedIndicesWarnAtTheSameLine) {
  // The warning names the line of the first face with a 0 index: the stream counts lines itself.
  const std::string xml = with("1 3 4\n", "\n\n0 2 3\n", with("1 2 3\n", "0 1 2\n"));
  const Outcome streamed = loadText(xml, true);
  ASSERT_TRUE(streamed.ok) << streamed.error;
  ASSERT_FALSE(streamed.warnings.empty());
  EXPECT_NE(streamed.warnings[0].find("s.xml:38:"), std::string::npos) << streamed.warnings[0];
  expectSameText(xml, true, "zero-based");
}

TEST(SceneStream, IndexFormsNormalsAndTextureCoordinates) {
  std::string xml = with("</vertexdata>\n", "</vertexdata>\n<texturedata>0 0 1 0 1 1 0 1</texturedata>"
                                                       "<normaldata>0 0 1 0 0 1 0 0 1 0 0 1</normaldata>\n");
  xml = with("1 3 4\n", "1//1 3//3 4//4\n", with("1 2 3\n", "1/1/1 2/2/2 3/3/3\n", xml));
  expectSameText(xml, true, "v/t/n and v//n");
}

TEST(SceneStream, ByteOrderMarkCarriageReturnsAndCaseAreStreamed) {
  std::string xml = "\xEF\xBB\xBF" + with("</vertexdata>", "</VertexData>", with("<vertexdata>", "<VertexData>"));
  std::string crlf;
  for (char c : xml) crlf += c == '\n' ? std::string("\r\n") : std::string(1, c);
  expectSameText(crlf, true, "BOM, CRLF, VertexData");
}

TEST(SceneStream, SeveralMeshesTakeTheirOwnFaces) {
  const std::string second = "<mesh id=\"b\">\n<materialid>red</materialid>\n<faces>2 3 4\n</faces>\n</mesh>\n";
  const std::string empty = "<mesh id=\"c\">\n<materialid>red</materialid>\n<faces></faces>\n</mesh>\n";
  expectSameText(with("</objects>", second + empty + second + "</objects>"), true, "four meshes");
}

TEST(SceneStream, RepairedTagsAroundBlocksAreStreamed) {
  // A misspelt closing tag after a block, and one left open before its parent closes: the repair pass
  // sees the skeleton's tags as the file's.
  expectSameText(with("</vertexdata>", "</vertexdta>"), true, "misspelt closing tag");
  expectSameText(with("1 3 4\n</faces>\n", "1 3 4\n"), true, "<faces> left open");
  expectSameText(with("</vertexdata>", "</vertexdta>"), false, "strict: the repair is an error", true);
}

// A scene whose blocks are longer than the 1 MiB pieces the file is read in, with numbers and lines that straddle
// them: n vertices and about n faces.
std::string longBlocksXml(int n) {
  std::string vertices, faces;
  char number[96];
  for (int i = 0; i < n; ++i) {
    std::snprintf(number, sizeof number, "%.17g %.17g %.17g\n", i * 0.001 - 3.0, (i % 977) * 1e-3, -2.0 - i * 1e-6);
    vertices += number;
    if (i + 2 < n) {
      std::snprintf(number, sizeof number, "%d %d %d%s", i + 1, i + 2, i + 3, i % 7 ? " " : "\n");
      faces += number;
    }
  }
  const std::string xml = with("-1 -1 -2\n1 -1 -2\n1 1 -2\n-1 1 -2\n", vertices);
  return with("1 2 3\n1 3 4\n", faces, xml);
}

TEST(SceneStream, BlocksLongerThanAPieceAreStreamedWhole) {
  const int n = 120000;
  const std::string xml = longBlocksXml(n);
  ASSERT_GT(xml.size(), 3u << 20);
  expectSameText(xml, true, "long blocks");

  const fs::path dir = testing::testOutputDirectory() / "scene_stream";
  fs::create_directories(dir);
  const fs::path file = dir / "long.xml";
  std::ofstream(file, std::ios::binary) << xml;
  const Outcome streamed = loadFile(file, true);
  ASSERT_TRUE(streamed.ok) << streamed.error;
  EXPECT_EQ(streamed.scene.vertices.size(), static_cast<std::size_t>(n));
  EXPECT_GT(streamed.scene.triangles.size(), static_cast<std::size_t>(n / 2));  // less the degenerate ones
  expectSame(streamed, loadFile(file, false), "long file");
}

Outcome loadTextOn(const std::string& xml, int threads) {
  LoadOptions options;
  options.loadTexture = false;
  options.threads = threads;
  return outcomeOf([&] { return loadSceneText(xml, "s.xml", ".", options); });
}

// On two threads (the faces on one, the vertices on the other) a big file is the same scene, with the same
// messages, as on one and as the DOM reads it; so is a file either side gives up on (the DOM then reports it). The
// name puts it in the ThreadSanitizer run.
TEST(SceneStreamThreads, ABigFileParsedOnTwoThreadsIsTheSameScene) {
  const std::string xml = longBlocksXml(120000);
  {
    const scene_loading::StreamedBlocks streamed = scene_loading::streamSkeleton(readerOf(xml), xml.size());
    std::uint64_t faceBytes = 0, otherBytes = 0;
    for (const scene_loading::StreamedBlock& b : streamed.blocks)
      (b.tag == scene_loading::Tag::Faces ? faceBytes : otherBytes) += b.end - b.begin;
    ASSERT_GT(faceBytes, 1u << 20) << "both sides big enough to be parsed apart";
    ASSERT_GT(otherBytes, 1u << 20);
  }
  EXPECT_TRUE(streams(xml, false, 2)) << "read by the stream itself, not left to the DOM";
  const Outcome two = loadTextOn(xml, 2);
  ASSERT_TRUE(two.ok) << two.error;
  EXPECT_EQ(two.scene.vertices.size(), 120000u);
  expectSame(two, loadTextOn(xml, 1), "two threads against one");
  expectSame(two, loadText(xml, false), "two threads against the DOM");

  const std::size_t vertexMiddle = xml.find("\n", xml.size() / 4) + 1;
  const std::size_t faceMiddle = xml.find("\n", xml.rfind("</faces>") - 200) + 1;
  for (const auto& [at, what] : {std::pair{vertexMiddle, "a bad vertex"}, std::pair{faceMiddle, "a bad face"}}) {
    std::string bad = xml;
    bad.insert(at, "x ");
    const Outcome failed = loadTextOn(bad, 2);
    EXPECT_FALSE(failed.ok) << what;
    expectSame(failed, loadText(bad, false), what);
  }
}

TEST(SceneStream, TheSkeletonNeverHoldsABlocksText) {
  // The first pass takes each block's text back out of the skeleton; it must not first copy a whole piece of it in,
  // touching a megabyte of fresh memory only to give it back.
  const std::string xml = longBlocksXml(120000);
  const scene_loading::StreamedBlocks streamed = scene_loading::streamSkeleton(readerOf(xml), xml.size());
  ASSERT_EQ(streamed.blocks.size(), 2u);
  const auto lines = static_cast<std::size_t>(std::count(xml.begin(), xml.end(), '\n'));
  EXPECT_LE(streamed.skeleton.size(), lines + 4096) << "the markup, and a newline for each line of a block's text";
  EXPECT_LT(streamed.skeleton.capacity(), 2 * streamed.skeleton.size() + (std::size_t{256} << 10))
      << "grown no further than what it holds asks";
}

TEST(SceneStream, ArraysHoldAboutWhatTheBlocksGive) {
  // A big scene's arrays are reserved from its text before it is read. Faces written "v//n" with five-digit
  // indices are ~40 bytes each: an estimate from the shortest possible face ("1 2 3") reserved six times the
  // faces, 24 MB of triangles and face attributes for a 1e5-triangle sphere's 3.6 MB, against a budget of 20 MB
  // for the whole render (docs/PERFORMANCE.md, "The loader").
  // Either way of reading, every array may hold at most half again what it has (here the estimate, from the
  // first faces with their shorter indices, reserves a third more).
  const int n = 60000;
  std::string vertices, normals, faces;
  char line[128];
  for (int i = 0; i < n; ++i) {
    std::snprintf(line, sizeof line, "%.9g %.9g -2\n", i * 1e-3, (1LL * i * i % 1009) * 1e-3);  // no three in a line
    vertices += line;
    std::snprintf(line, sizeof line, "0 %.6g 1\n", (i % 13) * 1e-2);
    normals += line;
    if (i + 2 < n) {
      std::snprintf(line, sizeof line, "%d//%d %d//%d %d//%d\n", i + 1, i + 1, i + 2, i + 2, i + 3, i + 3);
      faces += line;
    }
  }
  std::string xml = with("-1 -1 -2\n1 -1 -2\n1 1 -2\n-1 1 -2\n</vertexdata>\n",
                         vertices + "</vertexdata>\n<normaldata>\n" + normals + "</normaldata>\n");
  xml = with("1 2 3\n1 3 4\n", faces, xml);
  ASSERT_TRUE(streams(xml));
  for (const bool stream : {true, false}) {
    SCOPED_TRACE(stream ? "streamed" : "from the DOM");
    const Outcome out = loadText(xml, stream);
    ASSERT_TRUE(out.ok) << out.error;
    const Scene& scene = out.scene;
    ASSERT_EQ(scene.vertices.size(), static_cast<std::size_t>(n));
    ASSERT_EQ(scene.normals.size(), static_cast<std::size_t>(n));
    ASSERT_EQ(scene.triangles.size(), static_cast<std::size_t>(n - 2));
    ASSERT_EQ(scene.faceAttributes.size(), scene.triangles.size());
    const auto atMostHalfMore = [](std::size_t capacity, std::size_t size) { return capacity * 2 <= size * 3; };
    EXPECT_PRED2(atMostHalfMore, scene.vertices.capacity(), scene.vertices.size());
    EXPECT_PRED2(atMostHalfMore, scene.normals.capacity(), scene.normals.size());
    EXPECT_PRED2(atMostHalfMore, scene.triangles.capacity(), scene.triangles.size());
    EXPECT_PRED2(atMostHalfMore, scene.faceAttributes.capacity(), scene.faceAttributes.size());
  }
}

// ---------------------------------------------------------------- what it leaves to the ordinary reading

TEST(SceneStream, WhatOnlyTheDomCanReadIsReadTheSame) {
  struct Case {
    const char* what;
    std::string from, to;
  };
  const Case cases[] = {
      {"a comment inside <faces>", "1 3 4\n", "<!-- c -->1 3 4\n"},
      {"CDATA inside <vertexdata>", "-1 1 -2\n", "<![CDATA[-1 1 -2]]>\n"},
      {"numbers glued by a sign", "\n1 1 -2\n", "\n1 1-2\n"},
      {"an entity", "\n1 1 -2\n", "\n1 1 -&#50;\n"},
      {"a word among the numbers", "\n1 1 -2\n", "\n1 one -2\n"},
      {"not a multiple of 3", "\n1 1 -2\n", "\n1 1\n"},
      {"a value beyond double", "\n1 1 -2\n", "\n1 1 -2e400\n"},
      {"a negative face index", "1 3 4\n", "1 -3 4\n"},
      {"mixed index forms", "1 3 4\n", "1 3//1 4\n"},
      {"faces not a multiple of 3", "1 3 4\n", "1 3\n"},
      {"an index out of range", "1 3 4\n", "1 3 9\n"},
      {"a child element inside <faces>", "1 3 4\n", "<x/>1 3 4\n"},
      // The repair pass blanks the stray tag: the DOM reads one text, in which '-->4' is no index.
      {"a stray closing tag inside <faces>", "1 2 3\n1 3 4\n", "\n</diffuse>1 2 3\n1 3 -->4\n"},
      {"a stray closing tag between faces", "1 2 3\n1 3 4\n", "1 2 3\n</diffuse>1 3 4\n"},
      {"the marker spelt out", "<materialid>red</materialid>", "<materialid>@stream:0</materialid>"},
      {"the file ends inside <faces>", "1 3 4\n</faces>\n</mesh>\n</objects>\n</scene>\n", "1 3 4\n"},
      {"two <vertexdata>", "<objects>", "<vertexdata>0 0 0</vertexdata>\n<objects>"},
      {"<faces> outside a mesh", "<objects>", "<faces>1 2 3</faces>\n<objects>"},
      {"a lone carriage return in a block", "\n1 1 -2\n", "\n1 1 -2\r"},
      {"a NUL byte", "\n1 1 -2\n", std::string("\n1 1 -2\0\n", 9)},
  };
  for (const Case& c : cases) expectSameText(with(c.from, c.to), false, c.what);
}

TEST(SceneStream, ASelfClosingFacesIsReadFromTheDom) {
  // <faces/> has no text for the stream to take: the walk reads it from the DOM, which is exact only while no
  // streamed faces are in the scene.
  const std::string empty = "<mesh id=\"e\">\n<materialid>red</materialid>\n<faces/>\n</mesh>\n";
  expectSameText(with("</objects>", empty + "</objects>"), false, "<faces/> after streamed faces");
  expectSameText(with("<faces>\n1 2 3\n1 3 4\n</faces>", "<faces/>"), true, "<faces/> alone");
}

}  // namespace
}  // namespace rayview
