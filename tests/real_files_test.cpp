// Every scene file we have from the outside world, with the outcome it must have (SPEC section 2).
// A new file under handout/ or peer-scenes/ fails TableCoversEveryFile until it gets a row here.

#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "rayview/prepared_scene.h"
#include "rayview/scene_loader.h"
#include "rayview/tracer.h"
#include "support/image_compare.h"

namespace rayview {
namespace {

namespace fs = std::filesystem;

const fs::path kShared = RAYVIEW_SHARED_DIR;

struct ExpectedWarning {
  int line;
  std::string part;
};

struct Row {
  std::string path;  // relative to the shared folder
  bool loads;
  std::size_t triangles = 0;                // when it loads
  bool texture = false;                     // a texture image is read
  std::vector<ExpectedWarning> warnings{};  // all of them, when it loads
  int errorLine = 0;                        // when it fails
  std::string error{};
};

Row loads(std::string path, std::size_t triangles, bool texture, std::vector<ExpectedWarning> warnings = {}) {
  return Row{std::move(path), true, triangles, texture, std::move(warnings)};
}
Row fails(std::string path, int line, std::string error) {
  return Row{std::move(path), false, 0, false, {}, line, std::move(error)};
}

const std::string kBackgroundColor = "<backgroundColor> read as <background> (the handout example's spelling";
const std::string kMirrorAlias = "<mirrorreflactance> read as <mirrorreflectance> (misspelled element name)";
const std::string kZeroBased = "face indices are 0-based (vertex indices include 0 and never reach the count)";
const std::string kGlued = "<nearPlane>: numbers not separated by whitespace in '1-1'";
const std::string kCameras = "<Cameras> has ";
const std::string kSphere = "<Sphere> is a CENG477 object rayview does not render (triangle meshes only): dropped, the image lacks it";
const std::string kRepeatedFaces = "faces repeat the three vertices of an earlier face";

const std::vector<Row>& table() {
  static const std::vector<Row> rows = {
      // ---- the handout (SPEC section 2)
      loads("handout/example_2024.xml", 2, false,
            {{3, kBackgroundColor},
             {28, "closing tag </traingularlight> read as </triangularlight> (it closes <triangularlight> opened at line 23)"},
             {60, "stray text '...' ignored"}}),
      loads("handout/example_2024_skeleton_typos.xml", 3, false,
            {{16, "closing tag </intensity> read as </intesity>"},
             {16, "<intesity> read as <intensity> (misspelled element name)"},
             {23, "closing tag </traingularlight> read as </triangularlight>"},
             {27, "closing tag </ambinet> read as </ambient>"},
             {31, "closing tag </mirrorreflancance> read as </mirrorreflectance>"},
             {34, "closing tag </ambinet> read as </ambient>"},
             {38, "closing tag </mirrorreflanctance> read as </mirrorreflactance>"},
             {38, kMirrorAlias}}),
      fails("handout/skeleton_2024.xml", 2, "<maxraytracedepth>: expected a non-negative integer, found 'n'"),

      // ---- AhmetKadir: one handout copy, one partial conversion, and METU CENG477 scenes (the loader's CENG477 dialect)
      loads("peer-scenes/AhmetKadir__Simple-Ray-Tracer/scene.xml", 2, false,
            {{3, kBackgroundColor}, {12, "stray text '3' ignored"}, {34, kMirrorAlias}, {55, "stray text '...' ignored"}}),
      loads("peer-scenes/AhmetKadir__Simple-Ray-Tracer/sample_scenes/bunny.xml", 4968, false,
            {{2, "<backgroundcolor> read as <background>"}}),
      // (read natively as the CENG477 dialect; its spheres are dropped with a warning, docs/scene-format.md)
      loads("peer-scenes/AhmetKadir__Simple-Ray-Tracer/sample_scenes/cornellbox.xml", 10, false,
            {{9, kCameras + "3 cameras: rendering the first"}, {142, kSphere + " (2 times; the first is shown)"}}),
      loads("peer-scenes/AhmetKadir__Simple-Ray-Tracer/sample_scenes/dragon_lowres.xml", 11973, false,
            {{6042, "4 " + kRepeatedFaces}}),
      loads("peer-scenes/AhmetKadir__Simple-Ray-Tracer/sample_scenes/horse_and_mug.xml", 31582, false,
            {{47556, kSphere + " (2 times; the first is shown)"}}),
      fails("peer-scenes/AhmetKadir__Simple-Ray-Tracer/sample_scenes/mirror_spheres.xml", 67,
            "no object of the scene can be rendered: rayview renders triangle meshes only, and the objects here are not "
            "(the first is <Sphere id=\"1\">)"),
      loads("peer-scenes/AhmetKadir__Simple-Ray-Tracer/sample_scenes/scienceTree.xml", 2240, false,
            {{9, kCameras + "3 cameras: rendering the first"}}),
      loads("peer-scenes/AhmetKadir__Simple-Ray-Tracer/sample_scenes/simple.xml", 3, false, {{63, kSphere}}),
      loads("peer-scenes/AhmetKadir__Simple-Ray-Tracer/sample_scenes/simple_reflectance.xml", 2, false, {{66, kSphere}}),
      loads("peer-scenes/AhmetKadir__Simple-Ray-Tracer/sample_scenes/simple_shading.xml", 2, false, {{62, kSphere}}),

      // ---- GtuOdevlerEmirhanAltunel: 0-based cat/chest/cube, textures by absolute and ../ paths
      loads("peer-scenes/GtuOdevlerEmirhanAltunel__CSE461-HW1/assets/scene copy.xml", 30, true,
            {{3, kBackgroundColor}, {38, kMirrorAlias + " (2 times; the first is shown)"}}),
      loads("peer-scenes/GtuOdevlerEmirhanAltunel__CSE461-HW1/assets/scene.xml", 24, true,
            {{3, kBackgroundColor}, {32, kMirrorAlias}, {73, "12 " + kRepeatedFaces}}),
      loads("peer-scenes/GtuOdevlerEmirhanAltunel__CSE461-HW1/assets/scene_cat.xml", 70576, false,
            {{3, kBackgroundColor}, {34, kMirrorAlias}, {35334, kZeroBased}}),
      loads("peer-scenes/GtuOdevlerEmirhanAltunel__CSE461-HW1/assets/scene_chest.xml", 728, false,
            {{3, kBackgroundColor}, {8, kGlued}, {30, kMirrorAlias}, {448, kZeroBased}}),
      loads("peer-scenes/GtuOdevlerEmirhanAltunel__CSE461-HW1/assets/scene_cube.xml", 12, false,
            {{1, "no <ambientlight>: using black (0 0 0)"}, {3, kBackgroundColor}, {23, kMirrorAlias}, {41, kZeroBased}}),
      loads("peer-scenes/GtuOdevlerEmirhanAltunel__CSE461-HW1/assets/scene_orig.xml", 24, false,
            {{3, kBackgroundColor}, {30, kMirrorAlias}, {71, "12 " + kRepeatedFaces},
             {69, "texture image \"my_texture_only_texture.png\" could not be read (tried "}}),

      // ---- Kurtburakk: <textureimage> names the peer's OUTPUT file, never shipped
      loads("peer-scenes/Kurtburakk__Computer-Graphics-Cse-461/RayTracer/PA1/cghw1/examplexml/example.xml", 24, false,
            {{3, kBackgroundColor}, {30, kMirrorAlias}, {69, "texture image \"image_file_name.png\" could not be read"},
             {71, "12 " + kRepeatedFaces}}),
      loads("peer-scenes/Kurtburakk__Computer-Graphics-Cse-461/RayTracer/PA1/cghw1/examplexml/test1.xml", 4, false,
            {{3, kBackgroundColor}, {24, kMirrorAlias + " (2 times"}, {57, "texture image \"test1.png\" could not be read"}}),
      loads("peer-scenes/Kurtburakk__Computer-Graphics-Cse-461/RayTracer/PA1/cghw1/examplexml/test2.xml", 10, false,
            {{3, kBackgroundColor}, {28, kMirrorAlias + " (3 times"}, {87, "texture image \"test2.png\" could not be read"}}),
      loads("peer-scenes/Kurtburakk__Computer-Graphics-Cse-461/RayTracer/PA1/cghw1/examplexml/test3.xml", 17, false,
            {{3, kBackgroundColor}, {38, kMirrorAlias + " (4 times"}, {126, "texture image \"test3.png\" could not be read"}}),

      // ---- aeakyuz: absolute /home/... texture paths; capsule has 200 zero-area pole triangles
      loads("peer-scenes/aeakyuz__ray_tracer/scenes/capsule.xml", 10000, true,
            {{3, kBackgroundColor}, {38, kMirrorAlias},
             {15807, "mesh \"1\": 200 degenerate triangles skipped (zero area or a repeated vertex)"}}),
      loads("peer-scenes/aeakyuz__ray_tracer/scenes/my_scene.xml", 34, true,
            {{4, kBackgroundColor}, {29, kMirrorAlias + " (6 times"}}),
      loads("peer-scenes/aeakyuz__ray_tracer/scenes/old.xml", 1, false,
            {{3, kBackgroundColor}, {30, kMirrorAlias}, {59, "texture image \"textures/sun.png\" could not be read"}}),
      loads("peer-scenes/aeakyuz__ray_tracer/scenes/sample.xml", 24, false,
            {{3, kBackgroundColor}, {30, kMirrorAlias}, {71, "12 " + kRepeatedFaces},
             {69, "texture image \"/home/alierdem/Desktop/graphics461/hw1/textures/gosling.jpeg\" could not be read"}}),
      loads("peer-scenes/aeakyuz__ray_tracer/scenes/scene2.xml", 2, true,
            {{3, kBackgroundColor}, {38, kMirrorAlias + " (2 times"}}),
      loads("peer-scenes/aeakyuz__ray_tracer/scenes/test.xml", 3, true, {{3, kBackgroundColor}, {30, kMirrorAlias}}),

      // ---- akusgulu: the 2023 format, spec spelling
      loads("peer-scenes/akusgulu__raytracer/scenes/scene1.xml", 14, false),
      loads("peer-scenes/akusgulu__raytracer/scenes/scene2.xml", 978, false,
            {{20, "stray text '...' ignored"}, {661, "1 face repeats the three vertices of an earlier face"}}),
      loads("peer-scenes/akusgulu__raytracer/scenes/scene3.xml", 25860, false, {{13442, "48 " + kRepeatedFaces}}),

      // ---- bashtag: textures relative to the repository root (./assets/textures/...)
      loads("peer-scenes/bashtag__Simple-Ray-Tracer/assets/scenes/scene_3_meshes.xml", 1238, true,
            {{5, kBackgroundColor}, {32, kMirrorAlias + " (2 times"}, {1751, "6 " + kRepeatedFaces}}),
      loads("peer-scenes/bashtag__Simple-Ray-Tracer/assets/scenes/scene_3_meshes_triangular_light.xml", 1238, true,
            {{5, kBackgroundColor}, {32, kMirrorAlias + " (2 times"}, {1751, "6 " + kRepeatedFaces}}),
      loads("peer-scenes/bashtag__Simple-Ray-Tracer/assets/scenes/scene_3_meshes_triangular_light_mirror.xml", 1238, true,
            {{5, kBackgroundColor}, {32, kMirrorAlias + " (2 times"}, {1751, "6 " + kRepeatedFaces}}),
      loads("peer-scenes/bashtag__Simple-Ray-Tracer/assets/scenes/scene_low_tree.xml", 2463, true,
            {{4, kBackgroundColor}, {31, kMirrorAlias}, {5175, "mesh \"1\": 3 degenerate triangles skipped"},
             {5175, "10 " + kRepeatedFaces}}),
      loads("peer-scenes/bashtag__Simple-Ray-Tracer/assets/scenes/scene_sphere_point_light.xml", 7936, true,
            {{5, kBackgroundColor}, {32, kMirrorAlias}}),
      loads("peer-scenes/bashtag__Simple-Ray-Tracer/assets/scenes/scene_sphere_triangular_light.xml", 7936, true,
            {{5, kBackgroundColor}, {32, kMirrorAlias}}),

      // ---- borankurut: 0-based cat/chest, "-1  1-1 1" near planes, spheres (not part of the format)
      loads("peer-scenes/borankurut__CSE-461/RayTracing/scene_cat.xml", 70576, false,
            {{3, kBackgroundColor}, {8, kGlued}, {30, kMirrorAlias}, {35330, kZeroBased}}),
      loads("peer-scenes/borankurut__CSE-461/RayTracing/scene_chest.xml", 728, false,
            {{3, kBackgroundColor}, {8, kGlued}, {30, kMirrorAlias}, {448, kZeroBased}}),
      loads("peer-scenes/borankurut__CSE-461/RayTracing/scene_spheres.xml", 0, false,
            {{3, kBackgroundColor}, {8, kGlued}, {30, kMirrorAlias + " (3 times"},
             {54, "unknown element <sphere> ignored (only <mesh> objects are part of the format) (4 times"}}),

      // ---- mertugr: spec spelling, string material ids, v//n and v/t/n faces, PPM and PNG textures
      loads("peer-scenes/mertugr__mesh-trace/scenes/cube_simple.xml", 12, false),
      loads("peer-scenes/mertugr__mesh-trace/scenes/grid_large.xml", 2072, false),
      loads("peer-scenes/mertugr__mesh-trace/scenes/mirror_scene.xml", 26, false),
      loads("peer-scenes/mertugr__mesh-trace/scenes/textured_cube.xml", 12, true),
      loads("peer-scenes/mertugr__mesh-trace/scenes/textured_cube_png.xml", 12, true),
      loads("peer-scenes/mertugr__mesh-trace/scenes/two_cubes.xml", 26, false),
  };
  return rows;
}

std::string describe(const std::vector<Diagnostic>& warnings) {
  std::string all;
  for (const Diagnostic& d : warnings) all += "\n  " + d.format();
  return all;
}

class RealFile : public ::testing::TestWithParam<Row> {};

TEST_P(RealFile, HasItsExpectedOutcome) {
  RAYVIEW_SKIP_WITHOUT_SHARED();
  const Row& row = GetParam();
  const fs::path path = kShared / row.path;
  ASSERT_TRUE(fs::exists(path)) << path;
  if (!row.loads) {
    try {
      loadSceneFile(path);
      FAIL() << row.path << " loaded";
    } catch (const SceneError& e) {
      const std::string prefix = path.string() + ":" + std::to_string(row.errorLine) + ": error: ";
      EXPECT_EQ(std::string(e.what()).rfind(prefix, 0), 0u) << e.what();
      EXPECT_NE(std::string(e.what()).find(row.error), std::string::npos) << e.what();
    }
    return;
  }
  LoadedScene loaded;
  try {
    loaded = loadSceneFile(path);
  } catch (const SceneError& e) {
    FAIL() << e.what();
  }
  EXPECT_EQ(loaded.scene.triangles.size(), row.triangles);
  EXPECT_EQ(loaded.scene.texture.has_value(), row.texture);
  EXPECT_EQ(loaded.warnings.size(), row.warnings.size()) << describe(loaded.warnings);
  for (const ExpectedWarning& w : row.warnings) {
    const bool found = std::any_of(loaded.warnings.begin(), loaded.warnings.end(), [&](const Diagnostic& d) {
      return d.where.line == w.line && d.where.file == path.string() && d.message.find(w.part) != std::string::npos;
    });
    EXPECT_TRUE(found) << "missing warning at line " << w.line << ": " << w.part << describe(loaded.warnings);
  }
  // Whatever loads is a whole scene: every index resolved, every material real.
  const Scene& s = loaded.scene;
  ASSERT_EQ(wholenessProblem(s), "");
  // And it renders: every pixel finite, at a reduced resolution (same frustum) to keep the test quick.
  Scene small = s;
  const double shrink = std::min(1.0, 48.0 / std::max(s.camera.width, s.camera.height));
  small.camera.width = std::max(1, static_cast<int>(s.camera.width * shrink));
  small.camera.height = std::max(1, static_cast<int>(s.camera.height * shrink));
  auto geometry = prepareGeometry(small, AccelKind::Embree, BvhBuild::Interactive);
  ASSERT_TRUE(geometry);
  const Tracer tracer(small, *geometry, RenderSettings{});
  RayCounts counts;
  for (int y = 0; y < small.camera.height; ++y)
    for (int x = 0; x < small.camera.width; ++x) {
      const Color c = tracer.tracePixel(x, y, counts);
      ASSERT_TRUE(std::isfinite(c.x) && std::isfinite(c.y) && std::isfinite(c.z)) << "pixel " << x << "," << y;
    }
  EXPECT_EQ(counts.camera, static_cast<std::uint64_t>(small.camera.width) * small.camera.height);

  // Without warnings, strict mode has nothing to object to.
  if (row.warnings.empty()) {
    LoadOptions strict;
    strict.strict = true;
    EXPECT_NO_THROW(loadSceneFile(path, strict));
  }
}

std::string rowName(const ::testing::TestParamInfo<Row>& info) {
  std::string name = info.param.path;
  for (char& c : name)
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  return name;
}

INSTANTIATE_TEST_SUITE_P(SharedScenes, RealFile, ::testing::ValuesIn(table()), rowName);

TEST(RealFiles, TableCoversEveryFile) {
  RAYVIEW_SKIP_WITHOUT_SHARED();
  std::set<std::string> present;
  for (const fs::directory_entry& e : fs::directory_iterator(kShared / "handout"))
    if (e.path().extension() == ".xml") present.insert(fs::relative(e.path(), kShared).generic_string());
  for (const fs::directory_entry& e : fs::recursive_directory_iterator(kShared / "peer-scenes"))
    if (e.is_regular_file() && e.path().extension() == ".xml") present.insert(fs::relative(e.path(), kShared).generic_string());
  std::set<std::string> listed;
  for (const Row& row : table()) EXPECT_TRUE(listed.insert(row.path).second) << "listed twice: " << row.path;
  for (const std::string& p : present) EXPECT_TRUE(listed.count(p)) << "no expected outcome for " << p;
  for (const std::string& p : listed) EXPECT_TRUE(present.count(p)) << "listed but not present: " << p;
  EXPECT_EQ(present.size(), 3u + 44u);
}

// ---- conformance/ceng477: the converted scenes must load (warnings allowed, printed), with the manifest's counts.
TEST(RealFiles, Ceng477ConversionsLoad) {
  RAYVIEW_SKIP_WITHOUT_SHARED();
  const fs::path dir = kShared / "conformance" / "ceng477";
  std::map<std::string, std::size_t> manifestTriangles;
  std::ifstream manifest(dir / "manifest.tsv");
  std::string line;
  std::getline(manifest, line);  // header: scene, vintage, camera, resolution, triangles, ...
  while (std::getline(manifest, line)) {
    std::istringstream fields(line);
    std::string scene, vintage, camera, resolution, triangles;
    std::getline(fields, scene, '\t');
    std::getline(fields, vintage, '\t');
    std::getline(fields, camera, '\t');
    std::getline(fields, resolution, '\t');
    std::getline(fields, triangles, '\t');
    if (!scene.empty()) manifestTriangles[scene] = std::stoul(triangles);
  }
  std::size_t count = 0;
  for (const fs::directory_entry& e : fs::directory_iterator(dir)) {
    const std::string name = e.path().filename().string();
    if (e.path().extension() != ".xml" || name.find(".ceng477.") != std::string::npos) continue;
    ++count;
    SCOPED_TRACE(name);
    try {
      const LoadedScene loaded = loadSceneFile(e.path());
      for (const Diagnostic& d : loaded.warnings) std::cout << "  [ceng477] " << d.format() << "\n";
      const std::string stem = e.path().stem().string();
      ASSERT_TRUE(manifestTriangles.count(stem)) << stem << " is not in manifest.tsv";
      EXPECT_EQ(loaded.scene.triangles.size(), manifestTriangles[stem]);
      EXPECT_TRUE(loaded.scene.shadowRayEpsilon.has_value());
    } catch (const SceneError& error) {
      ADD_FAILURE() << error.what();
    }
  }
  EXPECT_EQ(count, 16u);
}

}  // namespace
}  // namespace rayview
