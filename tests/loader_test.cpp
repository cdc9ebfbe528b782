// The scene loader on small inline scenes: every repair, every error, with its line (SPEC section 2).
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "rayview/scene_loader.h"
#include "support/loader_scenes.h"

namespace rayview {
namespace {

using namespace loader_testing;

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
  ASSERT_EQ(s.lights.of<PointLight>().size(), 1u);
  EXPECT_EQ(s.lights.of<PointLight>()[0].id, "1");
  EXPECT_EQ(s.lights.of<PointLight>()[0].intensity, Color(100, 100, 100));
  ASSERT_EQ(s.materials.size(), 1u);
  EXPECT_EQ(s.materials[0].id, "red");
  EXPECT_EQ(s.materials[0].textureFactor, 0.0f);
  ASSERT_EQ(s.vertices.size(), 4u);
  ASSERT_EQ(s.triangles.size(), 2u);
  EXPECT_EQ(s.triangles[0].vertex[0], 0u);
  EXPECT_EQ(s.triangles[0].vertex[1], 1u);
  EXPECT_EQ(s.triangles[1].vertex[2], 3u);
  EXPECT_TRUE(s.faceAttributes.empty());  // plain faces: no per-face attributes held
  EXPECT_FALSE(s.attributesOf(0).hasTexCoords());
  EXPECT_FALSE(s.attributesOf(0).hasNormals());
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
  EXPECT_EQ(loaded.scene.lights.of<PointLight>().at(0).intensity, Color(100, 100, 100));
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
  ASSERT_EQ(loaded.scene.lights.of<TriangularLight>().size(), 1u);
  EXPECT_EQ(loaded.scene.lights.of<TriangularLight>()[0].id, "t");
  EXPECT_EQ(loaded.scene.lights.of<TriangularLight>()[0].vertex2, glm::dvec3(1, 0, 0));
  EXPECT_EQ(loaded.scene.lights.of<TriangularLight>()[0].intensity, Color(9, 9, 9));
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

// A repair by the XML pass followed by a repeated loader warning once wrote past the end of the
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
  EXPECT_EQ(loaded.scene.lights.of<TriangularLight>().size(), 1u);
  expectError(xml, 23, "</traingularlight>", strictOptions());
}

TEST(Loader, StrayClosingTagIsDropped) {
  const std::string xml = with("</lights>\n", "</lights>\n</pointlight>");  // line 19 now starts with it
  const LoadedScene loaded = load(xml);
  EXPECT_TRUE(hasWarning(loaded, 19, "stray closing tag </pointlight> dropped"));
  EXPECT_EQ(loaded.scene.lights.of<PointLight>().size(), 1u);
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
