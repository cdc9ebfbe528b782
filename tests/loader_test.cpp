// The scene loader on small inline scenes: every repair, every error, with its line (SPEC section 2).

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "rayview/scene_loader.h"

namespace rayview {
namespace {

namespace fs = std::filesystem;

// One element per line so that tests can name lines; keep the numbers in the comments right.
const std::string kBase =
    "<scene>\n"                                          // 1
    "<maxraytracedepth>1</maxraytracedepth>\n"           // 2
    "<background>1 2 3</background>\n"                   // 3
    "<camera>\n"                                         // 4
    "<position>0 0 0</position>\n"                       // 5
    "<gaze>0 0 -1</gaze>\n"                              // 6
    "<up>0 1 0</up>\n"                                   // 7
    "<nearplane>-1 1 -1 1</nearplane>\n"                 // 8
    "<neardistance>1</neardistance>\n"                   // 9
    "<imageresolution>4 3</imageresolution>\n"           // 10
    "</camera>\n"                                        // 11
    "<lights>\n"                                         // 12
    "<ambientlight>5 5 5</ambientlight>\n"               // 13
    "<pointlight id=\"1\">\n"                            // 14
    "<position>0 0 0</position>\n"                       // 15
    "<intensity>100 100 100</intensity>\n"               // 16
    "</pointlight>\n"                                    // 17
    "</lights>\n"                                        // 18
    "<materials>\n"                                      // 19
    "<material id=\"red\">\n"                            // 20
    "<ambient>1 0 0</ambient>\n"                         // 21
    "<diffuse>1 0 0</diffuse>\n"                         // 22
    "<specular>1 1 1</specular>\n"                       // 23
    "<phongexponent>1</phongexponent>\n"                 // 24
    "<mirrorreflectance>0 0 0</mirrorreflectance>\n"     // 25
    "</material>\n"                                      // 26
    "</materials>\n"                                     // 27
    "<vertexdata>\n"                                     // 28
    "-1 -1 -2\n"                                         // 29
    "1 -1 -2\n"                                          // 30
    "1 1 -2\n"                                           // 31
    "-1 1 -2\n"                                          // 32
    "</vertexdata>\n"                                    // 33
    "<objects>\n"                                        // 34
    "<mesh id=\"quad\">\n"                               // 35
    "<materialid>red</materialid>\n"                     // 36
    "<faces>\n"                                          // 37
    "1 2 3\n"                                            // 38
    "1 3 4\n"                                            // 39
    "</faces>\n"                                         // 40
    "</mesh>\n"                                          // 41
    "</objects>\n"                                       // 42
    "</scene>\n";                                        // 43

// kBase with one unique piece of text replaced.
std::string with(const std::string& from, const std::string& to, std::string text = kBase) {
  const std::size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << "test bug: '" << from << "' not in the scene";
  EXPECT_EQ(text.find(from, at + 1), std::string::npos) << "test bug: '" << from << "' is not unique";
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

LoadOptions strictOptions() {
  LoadOptions options;
  options.strict = true;
  return options;
}

LoadedScene load(const std::string& xml, const LoadOptions& options = {}) {
  return loadSceneText(xml, "t.xml", fs::temp_directory_path(), options);
}

// The full message of the error the scene raises ("" and a test failure when it loads).
std::string errorOf(const std::string& xml, const LoadOptions& options = {}) {
  try {
    load(xml, options);
  } catch (const SceneError& e) {
    EXPECT_EQ(std::string(e.what()), e.diagnostic().format());
    EXPECT_EQ(e.diagnostic().severity, Severity::Error);
    return e.what();
  } catch (const std::exception& e) {
    ADD_FAILURE() << "not a SceneError: " << e.what();
    return "";
  }
  ADD_FAILURE() << "the scene loaded";
  return "";
}

void expectError(const std::string& xml, int line, const std::string& part, const LoadOptions& options = {}) {
  const std::string message = errorOf(xml, options);
  const std::string prefix = line > 0 ? "t.xml:" + std::to_string(line) + ": error: " : "t.xml: error: ";
  EXPECT_EQ(message.rfind(prefix, 0), 0u) << message;
  EXPECT_NE(message.find(part), std::string::npos) << message;
}

// The warning at `line` containing `part`.
::testing::AssertionResult hasWarning(const LoadedScene& loaded, int line, const std::string& part) {
  std::string all;
  for (const Diagnostic& d : loaded.warnings) {
    if (d.where.line == line && d.message.find(part) != std::string::npos && d.severity == Severity::Warning &&
        d.where.file == "t.xml")
      return ::testing::AssertionSuccess();
    all += "\n  " + d.format();
  }
  return ::testing::AssertionFailure() << "no warning at line " << line << " with '" << part << "'; have:" << all;
}

// ---------------------------------------------------------------- the clean scene

TEST(Loader, BaseSceneLoadsWithoutWarnings) {
  const LoadedScene loaded = load(kBase, strictOptions());
  EXPECT_TRUE(loaded.warnings.empty());
  const Scene& s = loaded.scene;
  EXPECT_EQ(s.maxRayDepth, 1);
  EXPECT_EQ(s.background, Color(1, 2, 3));
  EXPECT_EQ(s.camera.width, 4);
  EXPECT_EQ(s.camera.height, 3);
  EXPECT_EQ(s.camera.gaze, glm::dvec3(0, 0, -1));
  EXPECT_EQ(s.camera.left, -1.0);
  EXPECT_EQ(s.camera.top, 1.0);
  EXPECT_EQ(s.ambientLight, Color(5, 5, 5));
  ASSERT_EQ(s.pointLights.size(), 1u);
  EXPECT_EQ(s.pointLights[0].id, "1");
  EXPECT_EQ(s.pointLights[0].intensity, Color(100, 100, 100));
  ASSERT_EQ(s.materials.size(), 1u);
  EXPECT_EQ(s.materials[0].id, "red");
  EXPECT_EQ(s.materials[0].textureFactor, 0.0f);
  ASSERT_EQ(s.vertices.size(), 4u);
  ASSERT_EQ(s.triangles.size(), 2u);
  EXPECT_EQ(s.triangles[0].vertex[0], 0u);
  EXPECT_EQ(s.triangles[0].vertex[1], 1u);
  EXPECT_EQ(s.triangles[1].vertex[2], 3u);
  EXPECT_FALSE(s.triangles[0].hasTexCoords());
  EXPECT_FALSE(s.triangles[0].hasNormals());
  ASSERT_EQ(s.meshes.size(), 1u);
  EXPECT_EQ(s.meshes[0].id, "quad");
  EXPECT_EQ(s.meshes[0].triangleCount, 2u);
  EXPECT_FALSE(s.shadowRayEpsilon.has_value());
}

TEST(Loader, NamesAreCaseInsensitiveWithoutWarnings) {
  std::string xml = with("<camera>", "<Camera>");
  xml = with("</camera>", "</CAMERA>", xml);
  xml = with("<nearplane>-1 1 -1 1</nearplane>", "<nearPlane>-1 1 -1 1</NEARPLANE>", xml);
  xml = with("<mesh id=\"quad\">", "<Mesh ID=\"quad\">", xml);
  const LoadedScene loaded = load(xml, strictOptions());
  EXPECT_TRUE(loaded.warnings.empty());
  EXPECT_EQ(loaded.scene.meshes.at(0).id, "quad");
}

// ---------------------------------------------------------------- aliases

TEST(Loader, AliasesLoadWithAWarningEach) {
  std::string xml = with("<background>1 2 3</background>", "<backgroundColor>1 2 3</backgroundColor>");
  xml = with("<intensity>100 100 100</intensity>", "<intesity>100 100 100</intesity>", xml);
  xml = with("<mirrorreflectance>0 0 0</mirrorreflectance>", "<mirrorreflactance>0.5 0 0</mirrorreflactance>", xml);
  const LoadedScene loaded = load(xml);
  EXPECT_TRUE(hasWarning(loaded, 3, "<backgroundColor> read as <background> (the handout example's spelling"));
  EXPECT_TRUE(hasWarning(loaded, 16, "<intesity> read as <intensity> (misspelled element name)"));
  EXPECT_TRUE(hasWarning(loaded, 25, "<mirrorreflactance> read as <mirrorreflectance>"));
  EXPECT_EQ(loaded.warnings.size(), 3u);
  EXPECT_EQ(loaded.scene.background, Color(1, 2, 3));
  EXPECT_EQ(loaded.scene.pointLights.at(0).intensity, Color(100, 100, 100));
  EXPECT_EQ(loaded.scene.materials.at(0).mirror, Color(0.5f, 0, 0));

  expectError(xml, 3, "<backgroundColor> read as <background>", strictOptions());
}

TEST(Loader, TriangularLightAndItsMisspelling) {
  const std::string light =
      "<traingularlight id=\"t\"><vertex1>0 0 0</vertex1><vertex2>1 0 0</vertex2><vertex3>0 1 0</vertex3>"
      "<intensity>9 9 9</intensity></traingularlight>";
  const std::string xml = with("</lights>", light + "</lights>");
  const LoadedScene loaded = load(xml);
  EXPECT_TRUE(hasWarning(loaded, 18, "<traingularlight> read as <triangularlight> (misspelled element name)"));
  ASSERT_EQ(loaded.scene.triangularLights.size(), 1u);
  EXPECT_EQ(loaded.scene.triangularLights[0].id, "t");
  EXPECT_EQ(loaded.scene.triangularLights[0].vertex2, glm::dvec3(1, 0, 0));
  EXPECT_EQ(loaded.scene.triangularLights[0].intensity, Color(9, 9, 9));
  expectError(xml, 18, "<traingularlight> read as <triangularlight>", strictOptions());
}

TEST(Loader, SameAliasIsReportedOnceWithACount) {
  std::string xml = with("<mirrorreflectance>0 0 0</mirrorreflectance>", "<mirrorreflactance>0 0 0</mirrorreflactance>");
  xml = with("</materials>",
             "<material id=\"b\"><ambient>0 0 0</ambient><diffuse>0 0 0</diffuse><specular>0 0 0</specular>"
             "<phongexponent>1</phongexponent><mirrorreflactance>0 0 0</mirrorreflactance></material></materials>",
             xml);
  const LoadedScene loaded = load(xml);
  ASSERT_EQ(loaded.warnings.size(), 1u);
  EXPECT_TRUE(hasWarning(loaded, 25, "(2 times; the first is shown)"));
}

// Issue 9: a repair by the XML pass followed by a repeated loader warning once wrote past the end of the
// repeat counts (ASan: heap-buffer-overflow) and lost the "(N times)" note. Both kinds share one list now.
TEST(Loader, RepeatCountIsRightAfterAnXmlRepair) {
  std::string xml = with("<ambient>1 0 0</ambient>", "<ambient>1 0 0</ambinet>");  // repaired, line 21
  xml = with("<mirrorreflectance>0 0 0</mirrorreflectance>", "<mirrorreflactance>0 0 0</mirrorreflactance>", xml);
  for (int extra = 0; extra < 3; ++extra)
    xml = with("</materials>",
               "<material id=\"m" + std::to_string(extra) + "\"><ambient>0 0 0</ambient><diffuse>0 0 0</diffuse>"
               "<specular>0 0 0</specular><phongexponent>1</phongexponent>"
               "<mirrorreflactance>0 0 0</mirrorreflactance></material></materials>",
               xml);
  const LoadedScene loaded = load(xml);
  EXPECT_TRUE(hasWarning(loaded, 21, "closing tag </ambinet> read as </ambient>"));
  EXPECT_TRUE(hasWarning(loaded, 25, "<mirrorreflactance> read as <mirrorreflectance> (misspelled element name) "
                                     "(4 times; the first is shown)"));
  EXPECT_EQ(loaded.warnings.size(), 2u);
}

// ---------------------------------------------------------------- closing-tag repairs

TEST(Loader, MisspelledClosingTagsAreRepaired) {
  struct Case {
    std::string from, to;
    int line;
    std::string warning;
  };
  const Case cases[] = {
      {"<ambient>1 0 0</ambient>", "<ambient>1 0 0</ambinet>", 21, "closing tag </ambinet> read as </ambient>"},
      {"<mirrorreflectance>0 0 0</mirrorreflectance>", "<mirrorreflectance>0 0 0</mirrorreflanctance>", 25,
       "closing tag </mirrorreflanctance> read as </mirrorreflectance>"},
      {"<mirrorreflectance>0 0 0</mirrorreflectance>", "<mirrorreflectance>0 0 0</mirrorreflancance>", 25,
       "closing tag </mirrorreflancance> read as </mirrorreflectance>"},
      {"<intensity>100 100 100</intensity>", "<intesity>100 100 100</intensity>", 16,
       "closing tag </intensity> read as </intesity>"},
      {"<specular>1 1 1</specular>", "<specular>1 1 1</speculra>", 23, "closing tag </speculra> read as </specular>"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.to);
    const std::string xml = with(c.from, c.to);
    const LoadedScene loaded = load(xml);
    EXPECT_TRUE(hasWarning(loaded, c.line, c.warning));
    EXPECT_TRUE(hasWarning(loaded, c.line, "opened at line " + std::to_string(c.line)));
    EXPECT_EQ(loaded.scene.triangles.size(), 2u);
    EXPECT_EQ(loaded.scene.materials.at(0).ambient, Color(1, 0, 0));
    expectError(xml, c.line, c.warning, strictOptions());
  }
}

TEST(Loader, MisspelledTriangularLightClosingTagIsRepaired) {
  const std::string light =
      "<triangularlight id=\"2\">\n<vertex1>0 0 0</vertex1>\n<vertex2>1 0 0</vertex2>\n<vertex3>0 1 0</vertex3>\n"
      "<intensity>9 9 9</intensity>\n</traingularlight>\n";
  // The light goes before </lights> (line 18): its closing tag lands on line 23.
  const std::string xml = with("</lights>\n", light + "</lights>\n");
  const LoadedScene loaded = load(xml);
  EXPECT_TRUE(hasWarning(loaded, 23, "closing tag </traingularlight> read as </triangularlight> (it closes "
                                     "<triangularlight> opened at line 18)"));
  EXPECT_EQ(loaded.scene.triangularLights.size(), 1u);
  expectError(xml, 23, "</traingularlight>", strictOptions());
}

TEST(Loader, StrayClosingTagIsDropped) {
  const std::string xml = with("</lights>\n", "</lights>\n</pointlight>");  // line 19 now starts with it
  const LoadedScene loaded = load(xml);
  EXPECT_TRUE(hasWarning(loaded, 19, "stray closing tag </pointlight> dropped"));
  EXPECT_EQ(loaded.scene.pointLights.size(), 1u);
  expectError(xml, 19, "stray closing tag </pointlight> dropped", strictOptions());

  const LoadedScene after = load(kBase + "</scene>\n");
  EXPECT_TRUE(hasWarning(after, 44, "stray closing tag </scene> dropped (there is no open element to close)"));
}

TEST(Loader, UnclosedLeafIsClosedBeforeItsParentCloses) {
  const std::string xml = with("<mirrorreflectance>0 0 0</mirrorreflectance>", "<mirrorreflectance>0 0 0");
  const LoadedScene loaded = load(xml);
  EXPECT_TRUE(hasWarning(loaded, 26, "<mirrorreflectance> opened at line 25 is not closed; closed before </material>"));
  EXPECT_EQ(loaded.scene.materials.size(), 1u);
  expectError(xml, 26, "is not closed", strictOptions());
}

TEST(Loader, UnrecoverableStructureIsALocatedError) {
  // </scene> where </camera> should be: <camera> has children, so closing it there is not clearly right.
  expectError(with("</camera>", "</scene>"), 11,
              "</scene> closes <scene> opened at line 1, but <camera> opened at line 4 is still open");
  // A closing tag that is a misspelling of an outer element, not of the open one.
  expectError(with("</pointlight>", "</lihgts>"), 17, "closing tag </lihgts> does not match <pointlight> opened at line 14");
  // A bare '<' in text.
  expectError(with("-1 1 -2\n", "-1 1 < -2\n"), 32, "'<' is not followed by an element name");
  expectError(with("<pointlight id=\"1\">", "<pointlight id=1>"), 14, "XML syntax error: malformed");
}

TEST(Loader, CommentsAndDeclarationsAreNotRepaired) {
  std::string xml = "<?xml version=\"1.0\"?>\n<!-- </ambinet> <scene> -->\n" + kBase;
  xml = with("<faces>\n", "<faces><!-- a comment </faces> -->\n", xml);
  const LoadedScene loaded = load(xml, strictOptions());
  EXPECT_TRUE(loaded.warnings.empty());
  EXPECT_EQ(loaded.scene.triangles.size(), 2u);
}

// ---------------------------------------------------------------- truncated files

TEST(Loader, TruncatedFileIsAnError) {
  const std::string cut = kBase.substr(0, kBase.find("1 1 -2\n"));  // ends inside <vertexdata>, on line 31
  expectError(cut, 31, "the file ends before <vertexdata> (opened at line 28) is closed; the file looks truncated");
  expectError(kBase.substr(0, kBase.find("</scene>")), 43, "the file ends before <scene> (opened at line 1) is closed");
  expectError(kBase.substr(0, kBase.find("data>\n<objects>")), 33, "the file ends inside a closing tag");
  expectError(kBase.substr(0, kBase.find("id=\"quad\"")), 35, "the file ends inside the tag <mesh");
  expectError(with("<objects>", "<objects><!-- x"), 34, "the file ends inside the comment");
}

TEST(Loader, EveryPrefixOfTheSceneIsRefusedNeverLoadedOrCrashed) {
  const std::size_t whole = kBase.find("</scene>") + std::string("</scene>").size();
  for (std::size_t n = 0; n < whole; ++n) {
    try {
      load(kBase.substr(0, n));
      ADD_FAILURE() << "a prefix of " << n << " bytes loaded";
    } catch (const SceneError&) {
    }
  }
}

// ---------------------------------------------------------------- numbers

TEST(Loader, WrongNumberCountIsAnError) {
  expectError(with("<position>0 0 0</position>\n<gaze>", "<position>0 0</position>\n<gaze>"), 5,
              "<position>: expected 3 numbers, found 2");
  expectError(with("<gaze>0 0 -1</gaze>", "<gaze>0 0 -1 7</gaze>"), 6, "<gaze>: expected 3 numbers, found 4");
  expectError(with("<nearplane>-1 1 -1 1</nearplane>", "<nearplane>-1 1 -1</nearplane>"), 8,
              "<nearplane>: expected 4 numbers, found 3");
  expectError(with("<imageresolution>4 3</imageresolution>", "<imageresolution>4</imageresolution>"), 10,
              "<imageresolution>: expected 2 integers (nx ny), found 1 number");
  expectError(with("<imageresolution>4 3</imageresolution>", "<imageresolution>4 3.5</imageresolution>"), 10,
              "<imageresolution>: expected 2 integers (nx ny), found '3.5'");
  expectError(with("<phongexponent>1</phongexponent>", "<phongexponent></phongexponent>"), 24,
              "<phongexponent>: expected 1 number, found 0");
  expectError(with("-1 1 -2\n", "-1 1 -2 5\n"), 28, "<vertexdata>: expected 3 numbers per vertex, found 13 numbers");
}

TEST(Loader, NonFiniteNumbersAreErrors) {
  expectError(with("<ambientlight>5 5 5</ambientlight>", "<ambientlight>5 nan 5</ambientlight>"), 13,
              "<ambientlight>: 'nan' is not a finite number");
  expectError(with("<position>0 0 0</position>\n<gaze>", "<position>0 inf 0</position>\n<gaze>"), 5,
              "'inf' is not a finite number");
  expectError(with("\n1 -1 -2\n", "\n1 -1e999 -2\n"), 30, "<vertexdata>: '-1e999' is not a finite number");
  expectError(with("<diffuse>1 0 0</diffuse>", "<diffuse>1 1e39 0</diffuse>"), 22,
              "'1e39' is not a finite number in single precision");
  // Underflow is harmless: it reads as (nearly) zero.
  EXPECT_EQ(load(with("\n1 1 -2\n", "\n1 1 -2e-400\n")).scene.vertices.at(2).z, 0.0);
}

TEST(Loader, GarbageNumbersAreErrorsAtTheirLine) {
  expectError(with("<up>0 1 0</up>", "<up>0 one 0</up>"), 7, "<up>: expected a number, found 'one'");
  expectError(with("\n1 1 -2\n", "\n1 1x -2\n"), 31, "<vertexdata>: expected a number, found '1x'");
  expectError(with("\n1 1 -2\n", "\n1,1,-2\n"), 31, "expected a number, found '1,1,-2'");
  expectError(with("<background>1 2 3</background>", "<background>r g b</background>"), 3,
              "<background>: expected a number, found 'r'");
}

TEST(Loader, NumbersGluedBySignAreReadWithAWarning) {
  const std::string xml = with("<nearplane>-1 1 -1 1</nearplane>", "<nearplane> -1  1-1 1 </nearplane>");
  const LoadedScene loaded = load(xml);
  EXPECT_TRUE(hasWarning(loaded, 8, "<nearplane>: numbers not separated by whitespace in '1-1'"));
  EXPECT_EQ(loaded.scene.camera.right, 1.0);
  EXPECT_EQ(loaded.scene.camera.bottom, -1.0);
  expectError(xml, 8, "numbers not separated by whitespace", strictOptions());
}

TEST(Loader, NumbersMayUseExponentsPlusSignsAndAnyWhitespace) {
  const LoadedScene loaded = load(with("<position>0 0 0</position>\n<gaze>", "<position>\t+1e0\r\n 2.5E-1 -.5 </position>\n<gaze>"));
  EXPECT_EQ(loaded.scene.camera.position, glm::dvec3(1.0, 0.25, -0.5));
}

TEST(Loader, MaxRayTraceDepthMustBeANonNegativeInteger) {
  for (const char* bad : {"n", "-1", "1.5", "1 2", ""}) {
    SCOPED_TRACE(bad);
    expectError(with("<maxraytracedepth>1</maxraytracedepth>", std::string("<maxraytracedepth>") + bad + "</maxraytracedepth>"),
                2, "<maxraytracedepth>: expected a non-negative integer, found");
  }
  expectError(with("<maxraytracedepth>1</maxraytracedepth>", "<maxraytracedepth>2000000</maxraytracedepth>"), 2,
              "2000000 is above the limit of 1000000");
  EXPECT_EQ(load(with("<maxraytracedepth>1</maxraytracedepth>", "<maxraytracedepth> 0 </maxraytracedepth>")).scene.maxRayDepth, 0);
}

// ---------------------------------------------------------------- faces and indices

TEST(Loader, ZeroBasedFacesAreDetectedWithOneWarning) {
  const std::string xml = with("1 2 3\n1 3 4\n", "0 1 2\n0 2 3\n");
  const LoadedScene loaded = load(xml);
  EXPECT_TRUE(hasWarning(loaded, 38, "face indices are 0-based (vertex indices include 0 and never reach the count)"));
  EXPECT_EQ(loaded.warnings.size(), 1u);
  ASSERT_EQ(loaded.scene.triangles.size(), 2u);
  EXPECT_EQ(loaded.scene.triangles[1].vertex[0], 0u);
  EXPECT_EQ(loaded.scene.triangles[1].vertex[2], 3u);
  expectError(xml, 38, "face indices are 0-based", strictOptions());
}

TEST(Loader, ZeroBasedDecisionIsPerFileOverAllMeshes) {
  // Mesh 1 alone looks 1-based (no 0), mesh 2 has a 0: the file is 0-based, so mesh 1's 3 is vertex 3 (0-based).
  const std::string second = "<mesh id=\"b\"><materialid>red</materialid><faces>0 1 2</faces></mesh>";
  const std::string xml = with("</objects>", second + "</objects>", with("1 2 3\n1 3 4\n", "1 2 3\n1 3 2\n"));
  const LoadedScene loaded = load(xml);
  EXPECT_TRUE(hasWarning(loaded, 42, "0-based"));
  ASSERT_EQ(loaded.scene.triangles.size(), 3u);
  EXPECT_EQ(loaded.scene.triangles[0].vertex[2], 3u);
  EXPECT_EQ(loaded.scene.meshes.at(1).id, "b");
  EXPECT_EQ(loaded.scene.triangles[2].mesh, 1u);
}

TEST(Loader, IndexOutOfRangeIsAnErrorAtTheFaceLine) {
  expectError(with("1 3 4\n", "1 3 5\n"), 39,
              "mesh \"quad\": vertex index 5 is out of range (the file has 4 vertices, indices 1..4)");
  // 0 and 4 both occur: neither 0-based nor 1-based.
  expectError(with("1 2 3\n1 3 4\n", "1 2 3\n0 3 4\n"), 39, "mesh \"quad\": vertex index 0 is out of range");
  // A 0 with an index past the count: 1-based, and the first 0 is the error.
  expectError(with("1 2 3\n1 3 4\n", "0 1 2\n0 2 9\n"), 38, "vertex index 0 is out of range (the file has 4 vertices, indices 1..4)");
  // Texture indices decide on their own: 0-based texture indices with 1-based vertices.
  const LoadedScene mixed = load(with("1 2 3\n1 3 4\n", "1/0 2/1 3/2\n1/0 3/2 4/3\n",
                                      with("</vertexdata>\n", "</vertexdata><texturedata>0 0 1 0 1 1 0 1</texturedata>\n")));
  EXPECT_TRUE(hasWarning(mixed, 38, "face indices are 0-based (texture indices include 0"));
  EXPECT_EQ(mixed.scene.triangles.at(1).texCoord[2], 3);
  EXPECT_EQ(mixed.scene.triangles.at(1).vertex[2], 3u);
}

TEST(Loader, FaceTokenErrors) {
  expectError(with("1 3 4\n", "1 3\n"), 37, "mesh \"quad\": <faces> has 5 vertex indices, not a multiple of 3");
  expectError(with("1 3 4\n", "1 -3 4\n"), 39, "face indices must be positive, found '-3'");
  expectError(with("1 3 4\n", "1 3 x\n"), 39, "expected a vertex index (v, v/t, v//n or v/t/n), found 'x'");
  expectError(with("1 3 4\n", "1 3 4/\n"), 39, "found '4/'");
  expectError(with("1 3 4\n", "1 3 4.0\n"), 39, "found '4.0'");
}

TEST(Loader, ObjStyleFaceTokens) {
  const std::string data =
      "</vertexdata><texturedata>0 0 1 0 1 1 0 1</texturedata><normaldata>0 0 1 0 0 -1</normaldata>";
  std::string xml = with("</vertexdata>\n", data + "\n");
  xml = with("1 2 3\n1 3 4\n", "1/1/2 2/2/2 3/3/2\n1//1 3//1 4//1\n", xml);
  const LoadedScene loaded = load(xml);
  EXPECT_TRUE(loaded.warnings.empty());
  ASSERT_EQ(loaded.scene.triangles.size(), 2u);
  const Triangle& a = loaded.scene.triangles[0];
  EXPECT_TRUE(a.hasTexCoords());
  EXPECT_TRUE(a.hasNormals());
  EXPECT_EQ(a.texCoord[2], 2);
  EXPECT_EQ(a.normal[0], 1);
  const Triangle& b = loaded.scene.triangles[1];
  EXPECT_FALSE(b.hasTexCoords());
  EXPECT_EQ(b.normal[1], 0);
  EXPECT_EQ(loaded.scene.texCoords.at(2), glm::vec2(1, 1));

  const LoadedScene vt = load(with("1 2 3\n1 3 4\n", "1/1 2/2 3/3\n1/1 3/3 4/4\n", with("</vertexdata>\n", data + "\n")));
  EXPECT_TRUE(vt.scene.triangles[1].hasTexCoords());
  EXPECT_FALSE(vt.scene.triangles[1].hasNormals());
  EXPECT_EQ(vt.scene.triangles[1].texCoord[2], 3);

  expectError(with("1 2 3\n1 3 4\n", "1/1/1 2/2/1 3/3/1\n1/5/1 3/3/1 4/4/1\n", with("</vertexdata>\n", data + "\n")), 39,
              "texture index 5 is out of range (the file has 4 <texturedata> coordinates, indices 1..4)");
  expectError(with("1 2 3\n1 3 4\n", "1//1 2//1 3//1\n"), 38, "normal index 1 is out of range (the file has no <normaldata> normals)");
  expectError(with("1 2 3\n1 3 4\n", "1/1/1 2 3/3/1\n", with("</vertexdata>\n", data + "\n")), 38,
              "a face mixes index forms");
}

TEST(Loader, DegenerateTrianglesAreSkippedWithOneWarningPerMesh) {
  const std::string xml = with("1 2 3\n1 3 4\n", "1 2 3\n1 1 3\n2 2 2\n");
  const LoadedScene loaded = load(xml, strictOptions());  // not a repair: a warning even in strict mode
  EXPECT_TRUE(hasWarning(loaded, 35, "mesh \"quad\": 2 degenerate triangles skipped (zero area or a repeated vertex)"));
  ASSERT_EQ(loaded.scene.triangles.size(), 1u);
  EXPECT_EQ(loaded.scene.meshes[0].triangleCount, 1u);
  // Zero area from collinear points.
  const LoadedScene collinear = load(with("-1 1 -2\n", "0 0 -2\n", with("1 2 3\n1 3 4\n", "1 2 3\n1 3 4\n")));
  EXPECT_TRUE(hasWarning(collinear, 35, "1 degenerate triangle skipped"));
  EXPECT_EQ(collinear.scene.triangles.size(), 1u);
}

TEST(Loader, RepeatedFacesAreKeptWithOneWarning) {
  // The second quad repeats both faces, one of them with the opposite winding.
  const LoadedScene loaded = load(with("1 2 3\n1 3 4\n", "1 2 3\n1 3 4\n3 2 1\n4 3 1\n"), strictOptions());
  EXPECT_TRUE(hasWarning(loaded, 35, "2 faces repeat the three vertices of an earlier face (the first in mesh \"quad\")"));
  EXPECT_EQ(loaded.scene.triangles.size(), 4u);  // kept: which one is seen is the renderer's tie rule
  EXPECT_TRUE(load(with("1 2 3\n1 3 4\n", "1 2 3\n1 3 4\n")).warnings.empty());
}

// ---------------------------------------------------------------- materials

TEST(Loader, MaterialIdsAreStringsAndMustResolve) {
  expectError(with("<materialid>red</materialid>", "<materialid>blue</materialid>"), 36,
              "mesh \"quad\": material \"blue\" is not defined (defined: \"red\")");
  expectError(with("</materials>", "<material id=\"red\"><ambient>0 0 0</ambient></material></materials>"), 27,
              "duplicate material id \"red\" (the first is at line 20)");
  expectError(with("<material id=\"red\">", "<material>"), 20, "<material> has no id attribute");
  expectError(with("<diffuse>1 0 0</diffuse>", ""), 20, "<material id=\"red\"> has no <diffuse>");
  expectError(with("<materialid>red</materialid>", ""), 35, "<mesh id=\"quad\"> has no <materialid>");
  EXPECT_EQ(load(with("<materialid>red</materialid>", "<materialid> red </materialid>")).scene.triangles.size(), 2u);
}

TEST(Loader, MaterialOptionalParts) {
  const LoadedScene noMirror = load(with("<mirrorreflectance>0 0 0</mirrorreflectance>", ""));
  EXPECT_TRUE(hasWarning(noMirror, 20, "<material id=\"red\"> has no <mirrorreflectance>; using 0 0 0"));
  const LoadedScene factor = load(with("<phongexponent>1</phongexponent>", "<phongexponent>1</phongexponent><texturefactor>0.25</texturefactor>"));
  EXPECT_EQ(factor.scene.materials[0].textureFactor, 0.25f);
  expectError(with("<phongexponent>1</phongexponent>", "<phongexponent>-2</phongexponent>"), 24, "<phongexponent>: must be >= 0");
}

// ---------------------------------------------------------------- defaults and structure

TEST(Loader, MissingOptionalElementsTakeDefaultsWithWarnings) {
  std::string xml = with("<maxraytracedepth>1</maxraytracedepth>", "");
  xml = with("<background>1 2 3</background>", "", xml);
  xml = with("<ambientlight>5 5 5</ambientlight>", "", xml);
  const LoadedScene loaded = load(xml, strictOptions());
  EXPECT_TRUE(hasWarning(loaded, 1, "no <maxraytracedepth>: using 0"));
  EXPECT_TRUE(hasWarning(loaded, 1, "no <background>: using black (0 0 0)"));
  EXPECT_TRUE(hasWarning(loaded, 1, "no <ambientlight>: using black (0 0 0)"));
  EXPECT_EQ(loaded.scene.maxRayDepth, 0);
  EXPECT_EQ(loaded.scene.background, Color(0));
  EXPECT_EQ(loaded.scene.ambientLight, Color(0));
}

TEST(Loader, MissingOrDuplicateRequiredElementsAreErrors) {
  const std::size_t begin = kBase.find("<camera>"), end = kBase.find("</camera>\n") + 10;
  std::string noCamera = kBase;
  noCamera.replace(begin, end - begin, "");
  expectError(noCamera, 1, "no <camera> element");
  expectError(with("<up>0 1 0</up>", ""), 4, "<camera> has no <up>");
  expectError(with("<intensity>100 100 100</intensity>", ""), 14, "<pointlight id=\"1\"> has no <intensity>");
  expectError(with("</camera>", "<gaze>0 0 1</gaze></camera>"), 11, "duplicate <gaze> inside <camera> (the first is at line 6)");
  expectError(with("<background>1 2 3</background>", "<background>1 2 3</background><background>0 0 0</background>"), 3,
              "duplicate <background> inside <scene>");
}

TEST(Loader, UnknownElementsAndStrayTextAreWarnings) {
  std::string xml = with("</camera>", "<fov>60</fov></camera>");
  xml = with("</objects>", "<sphere id=\"s\"><center>0 0 0</center></sphere>\n...\n</objects>", xml);
  const LoadedScene loaded = load(xml);
  EXPECT_TRUE(hasWarning(loaded, 11, "unknown element <fov> ignored"));
  EXPECT_TRUE(hasWarning(loaded, 42, "unknown element <sphere> ignored (only <mesh> objects are part of the format)"));
  EXPECT_TRUE(hasWarning(loaded, 43, "stray text '...' ignored"));
  EXPECT_EQ(loaded.scene.triangles.size(), 2u);
  expectError(xml, 11, "unknown element <fov> ignored", strictOptions());
  expectError(with("</objects>", "\n...\n</objects>"), 43, "stray text '...'", strictOptions());
  // A known element in the wrong place.
  const LoadedScene misplaced = load(with("</lights>", "<gaze>1 1 1</gaze></lights>"));
  EXPECT_TRUE(hasWarning(misplaced, 18, "element <gaze> is not expected inside <lights>; ignored"));
}

TEST(Loader, WrongRootOrEmptyFile) {
  expectError("", 0, "no <scene> element");
  expectError("  \n  ", 0, "no <scene> element");
  expectError("<!-- nothing -->\n", 0, "no <scene> element");
  expectError("<world>\n</world>\n", 1, "the root element is <world>, expected <scene>");
}

TEST(Loader, Ceng477ScenesAreRecognised) {
  const std::string ceng =
      "<Scene>\n<BackgroundColor>0 0 0</BackgroundColor>\n<MaxRecursionDepth>6</MaxRecursionDepth>\n"
      "<Cameras>\n<Camera id=\"1\"><Position>0 0 0</Position></Camera>\n</Cameras>\n</Scene>\n";
  expectError(ceng, 4, "this looks like a METU CENG477 scene");
  expectError(ceng, 4, "not the CSE 461 PA1 format");
}

// ---------------------------------------------------------------- camera (SPEC section 3)

TEST(Loader, CameraValidity) {
  struct Case {
    std::string from, to, message;
  };
  const Case cases[] = {
      {"<gaze>0 0 -1</gaze>", "<gaze>0 0 0</gaze>", "camera: <gaze> is the zero vector"},
      {"<up>0 1 0</up>", "<up>0 0 2</up>", "camera: <up> is parallel to <gaze>"},
      {"<up>0 1 0</up>", "<up>0 0 0</up>", "camera: <up> is the zero vector"},
      {"<nearplane>-1 1 -1 1</nearplane>", "<nearplane>1 1 -1 1</nearplane>", "camera: <nearplane> left and right are equal (1)"},
      {"<nearplane>-1 1 -1 1</nearplane>", "<nearplane>-1 1 2 2</nearplane>", "camera: <nearplane> bottom and top are equal (2)"},
      {"<neardistance>1</neardistance>", "<neardistance>0</neardistance>", "camera: <neardistance> must be positive, found 0"},
      {"<neardistance>1</neardistance>", "<neardistance>-1</neardistance>", "camera: <neardistance> must be positive, found -1"},
      {"<imageresolution>4 3</imageresolution>", "<imageresolution>0 3</imageresolution>", "camera: <imageresolution> must be positive, found 0 x 3"},
      {"<imageresolution>4 3</imageresolution>", "<imageresolution>4 -3</imageresolution>", "camera: <imageresolution> must be positive, found 4 x -3"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.to);
    expectError(with(c.from, c.to), 4, c.message);
  }
  // A slightly tilted up vector is fine (re-orthogonalised by the camera).
  EXPECT_NO_THROW(load(with("<up>0 1 0</up>", "<up>0 1 0.1</up>")));
}

TEST(Loader, HugeImagesAreRefusedUpFront) {
  expectError(with("<imageresolution>4 3</imageresolution>", "<imageresolution>200000 200000</imageresolution>"), 10,
              "<imageresolution>: 200000 x 200000 pixels is too large (the limit is 268435456 pixels");
  expectError(with("<imageresolution>4 3</imageresolution>", "<imageresolution>3000000000 1</imageresolution>"), 10,
              "is too large");
  expectError(with("<imageresolution>4 3</imageresolution>", "<imageresolution>99999999999999999999999 1</imageresolution>"), 10,
              "<imageresolution>: expected 2 integers (nx ny), found '99999999999999999999999'");
  EXPECT_EQ(load(with("<imageresolution>4 3</imageresolution>", "<imageresolution>16384 16384</imageresolution>")).scene.camera.width, 16384);
}

TEST(Loader, ShadowRayEpsilonExtension) {
  const std::string xml = with("<background>1 2 3</background>", "<background>1 2 3</background><shadowrayepsilon>1e-3</shadowrayepsilon>");
  const LoadedScene loaded = load(xml, strictOptions());
  ASSERT_TRUE(loaded.scene.shadowRayEpsilon.has_value());
  EXPECT_DOUBLE_EQ(*loaded.scene.shadowRayEpsilon, 1e-3);
  expectError(with("<background>1 2 3</background>", "<background>1 2 3</background><shadowrayepsilon>-1</shadowrayepsilon>"), 3,
              "<shadowrayepsilon>: must be >= 0");
}

// ---------------------------------------------------------------- textures

class LoaderTexture : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("rayview_loader_test_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) +
                                        "_" + ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_ / "repo" / "assets" / "scenes");
    fs::create_directories(dir_ / "repo" / "assets" / "textures");
    // A 2 x 1 binary PPM: red, green.
    std::ofstream(dir_ / "repo" / "assets" / "textures" / "t.ppm", std::ios::binary)
        << "P6\n2 1\n255\n" << std::string("\xff\x00\x00\x00\xff\x00", 6);
  }
  void TearDown() override { fs::remove_all(dir_); }

  LoadedScene loadIn(const std::string& texture, const LoadOptions& options = {}) {
    const fs::path scene = dir_ / "repo" / "assets" / "scenes" / "s.xml";
    std::ofstream(scene) << with("</objects>\n", "</objects>\n<textureimage>" + texture + "</textureimage>\n");
    return loadSceneFile(scene, options);
  }
  fs::path dir_;
};

TEST_F(LoaderTexture, RelativeToAnAncestorOfTheSceneDirectory) {
  const LoadedScene loaded = loadIn("./assets/textures/t.ppm");
  EXPECT_TRUE(loaded.warnings.empty());
  ASSERT_TRUE(loaded.scene.texture.has_value());
  EXPECT_EQ(loaded.scene.texture->width, 2);
  EXPECT_EQ(loaded.scene.texture->height, 1);
  ASSERT_EQ(loaded.scene.texture->rgb.size(), 6u);
  EXPECT_EQ(loaded.scene.texture->rgb[0], 255);
  EXPECT_EQ(loaded.scene.texture->rgb[4], 255);
  EXPECT_EQ(loaded.scene.textureImage, "./assets/textures/t.ppm");
  EXPECT_EQ(loaded.scene.sourcePath.filename(), "s.xml");
}

TEST_F(LoaderTexture, AbsolutePathFromAnotherMachineFallsBackToItsTail) {
  const LoadedScene loaded = loadIn("/home/someone/hw1/textures/t.ppm");
  EXPECT_TRUE(loaded.scene.texture.has_value());
}

TEST_F(LoaderTexture, MissingTextureIsAWarningNamingThePathsTried) {
  const LoadedScene loaded = loadIn("nowhere.png");
  EXPECT_FALSE(loaded.scene.texture.has_value());
  ASSERT_EQ(loaded.warnings.size(), 1u);
  const Diagnostic& w = loaded.warnings[0];
  EXPECT_EQ(w.where.line, 43);
  EXPECT_NE(w.message.find("texture image \"nowhere.png\" could not be read (tried "), std::string::npos) << w.message;
  EXPECT_NE(w.message.find((dir_ / "repo" / "assets" / "scenes" / "nowhere.png").string()), std::string::npos) << w.message;
  EXPECT_NE(w.message.find("rendering without the texture"), std::string::npos);
}

TEST_F(LoaderTexture, UnreadableTextureIsAWarning) {
  std::ofstream(dir_ / "repo" / "assets" / "scenes" / "bad.png") << "not an image";
  const LoadedScene loaded = loadIn("bad.png");
  EXPECT_FALSE(loaded.scene.texture.has_value());
  ASSERT_EQ(loaded.warnings.size(), 1u);
  EXPECT_NE(loaded.warnings[0].message.find("bad.png: not a readable image"), std::string::npos) << loaded.warnings[0].message;
}

TEST_F(LoaderTexture, NotLoadedWhenAskedNotTo) {
  LoadOptions options;
  options.loadTexture = false;
  const LoadedScene loaded = loadIn("nowhere.png", options);
  EXPECT_TRUE(loaded.warnings.empty());
  EXPECT_FALSE(loaded.scene.texture.has_value());
  EXPECT_EQ(loaded.scene.textureImage, "nowhere.png");
}

TEST(LoaderFile, MissingFileIsAnErrorNamingIt) {
  try {
    loadSceneFile("/nonexistent/dir/scene.xml");
    FAIL() << "loaded";
  } catch (const SceneError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("/nonexistent/dir/scene.xml: error: cannot open the scene file", 0), 0u) << e.what();
  }
  EXPECT_THROW(loadSceneFile(fs::temp_directory_path()), SceneError);
}

}  // namespace
}  // namespace rayview

namespace rayview {
namespace {

TEST(Loader, TextAndElementsOutsideTheRootAreWarnings) {
  const LoadedScene loaded = load("junk\n" + kBase + "<extra/>\nmore\n");
  EXPECT_TRUE(hasWarning(loaded, 1, "stray text 'junk' ignored"));
  EXPECT_TRUE(hasWarning(loaded, 45, "unknown element <extra> ignored"));
  EXPECT_TRUE(hasWarning(loaded, 46, "stray text 'more' ignored"));
}

TEST(Loader, LongMismatchedNamesDoNotStallTheRepair) {
  const std::string a(100000, 'a'), b(100000, 'b');
  // </bbb...> closes nothing: dropped; <aaa...> is a leaf, closed before </scene>; then the scene is empty.
  expectError("<scene><" + a + ">x</" + b + "></scene>", 1, "no <camera> element");
}

// Random byte edits of a valid scene: each either loads or is a SceneError; nothing else, no crash or hang.
TEST(Loader, MutatedScenesLoadOrFailCleanly) {
  std::uint32_t state = 12345;
  auto next = [&] { return state = state * 1664525u + 1013904223u; };
  const char alphabet[] = "<>/!-?\"'= \n0123456789.eE+-abcdefghijklmnopqrstuvwxyz&;";
  for (int round = 0; round < 3000; ++round) {
    std::string xml = kBase;
    const int edits = 1 + static_cast<int>(next() % 4);
    for (int e = 0; e < edits; ++e) {
      const std::size_t at = next() % xml.size();
      const char c = alphabet[next() % (sizeof alphabet - 1)];
      switch (next() % 3) {
        case 0: xml[at] = c; break;
        case 1: xml.insert(at, 1, c); break;
        default: xml.erase(at, 1 + next() % 8); break;
      }
    }
    try {
      const LoadedScene loaded = load(xml);
      for (const Triangle& t : loaded.scene.triangles)
        for (int k = 0; k < 3; ++k) ASSERT_LT(t.vertex[k], loaded.scene.vertices.size()) << xml;
    } catch (const SceneError& error) {
      EXPECT_NE(std::string(error.what()).find("t.xml"), std::string::npos);
    }
  }
}

}  // namespace
}  // namespace rayview
