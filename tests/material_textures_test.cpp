// Textures per material (rayview's <textureimage> inside a <material>): any number in a scene, each material shown
// with its own, read back exactly by the loader, the writer, the codec and the hash, and no change to a scene that
// names only the handout's one texture.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "rayview/metal_rough.h"
#include "rayview/scene_codec.h"
#include "rayview/scene_loader.h"
#include "rayview/scene_writer.h"
#include "support/image_compare.h"
#include "support/numerics_scenes.h"
#include "support/scene_compare.h"
#include "support/test_directory.h"

namespace rayview {
namespace {

namespace fs = std::filesystem;

// A 1x1 binary PPM of one colour.
void writePixel(const fs::path& path, unsigned char r, unsigned char g, unsigned char b) {
  std::ofstream(path, std::ios::binary) << "P6\n1 1\n255\n" << r << g << b;
}

// Three side-by-side quads seen face on, materials 1, 2 and 3 left to right, each shown wholly by its texture
// (factor 1); `ownTextures` are the <textureimage> lines inside materials 1 and 2, `sceneTexture` the scene's.
std::string threeQuads(const std::string& own1, const std::string& own2, const std::string& sceneTexture) {
  std::string xml = R"(<scene>
  <maxraytracedepth>0</maxraytracedepth>
  <background>0 0 0</background>
  <camera><position>0 0 0</position><gaze>0 0 -1</gaze><up>0 1 0</up>
    <nearplane>-1 1 -1 1</nearplane><neardistance>1</neardistance><imageresolution>6 2</imageresolution></camera>
  <lights><ambientlight>0 0 0</ambientlight></lights>
  <materials>
)";
  const std::string own[3] = {own1, own2, ""};
  for (int m = 0; m < 3; ++m)
    xml += "    <material id=\"" + std::to_string(m + 1) +
           "\"><ambient>0 0 0</ambient><diffuse>0 0 0</diffuse><specular>0 0 0</specular>"
           "<phongexponent>1</phongexponent><mirrorreflectance>0 0 0</mirrorreflectance>"
           "<texturefactor>1</texturefactor>" +
           (own[m].empty() ? "" : "<textureimage>" + own[m] + "</textureimage>") + "</material>\n";
  xml += "  </materials>\n  <vertexdata>\n";
  for (double x : {-2.0, -2.0 / 3.0, 2.0 / 3.0, 2.0})
    xml += "    " + std::to_string(x) + " -2 -2\n    " + std::to_string(x) + " 2 -2\n";
  xml += "  </vertexdata>\n  <texturedata>0 0 1 0 1 1 0 1</texturedata>\n";
  if (!sceneTexture.empty()) xml += "  <textureimage>" + sceneTexture + "</textureimage>\n";
  xml += "  <objects>\n";
  for (int m = 0; m < 3; ++m) {
    const int a = 2 * m + 1, b = a + 1, c = a + 2, d = a + 3;  // bottom-left, top-left, bottom-right, top-right
    xml += "    <mesh id=\"" + std::to_string(m + 1) + "\"><materialid>" + std::to_string(m + 1) + "</materialid><faces>" +
           std::to_string(a) + "/1 " + std::to_string(c) + "/2 " + std::to_string(d) + "/3 " + std::to_string(a) + "/1 " +
           std::to_string(d) + "/3 " + std::to_string(b) + "/4</faces></mesh>\n";
  }
  return xml + "  </objects>\n</scene>\n";
}

class MaterialTextures : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = testing::freshTestDirectory("rayview_material_textures");
    fs::create_directories(dir_ / "scene" / "maps");
    writePixel(dir_ / "scene" / "maps" / "red.ppm", 255, 0, 0);
    writePixel(dir_ / "scene" / "maps" / "blue.ppm", 0, 0, 255);
    writePixel(dir_ / "scene" / "green.ppm", 0, 255, 0);
  }
  void TearDown() override { fs::remove_all(dir_); }

  LoadedScene loadWritten(const std::string& xml) {
    const fs::path path = dir_ / "scene" / "s.xml";
    std::ofstream(path) << xml;
    return loadSceneFile(path);
  }
  fs::path dir_;
};

// The colour of pixel (i, j) of a render.
Color pixel(const Image& image, int i, int j) {
  const std::size_t at = (static_cast<std::size_t>(j) * image.width + i) * 3;
  return Color(image.rgb[at], image.rgb[at + 1], image.rgb[at + 2]);
}

TEST_F(MaterialTextures, EachMaterialShowsItsOwnAndTheRestTheScenes) {
  const LoadedScene loaded = loadWritten(threeQuads("maps/red.ppm", "maps/blue.ppm", "green.ppm"));
  EXPECT_TRUE(loaded.warnings.empty()) << loaded.warnings.front().format();
  const Scene& scene = loaded.scene;
  ASSERT_EQ(scene.materialTextures.size(), 2u);
  EXPECT_EQ(scene.materials[0].textureImage, "maps/red.ppm");
  EXPECT_EQ(scene.materials[2].textureImage, "");
  for (AccelKind accel : {AccelKind::Reference, AccelKind::Packet}) {
    const Image image = testing::renderChecked(scene, accel).image;
    for (int j = 0; j < 2; ++j) {
      EXPECT_EQ(pixel(image, 0, j), Color(255, 0, 0));
      EXPECT_EQ(pixel(image, 1, j), Color(255, 0, 0));
      EXPECT_EQ(pixel(image, 2, j), Color(0, 0, 255));
      EXPECT_EQ(pixel(image, 3, j), Color(0, 0, 255));
      EXPECT_EQ(pixel(image, 4, j), Color(0, 255, 0));
      EXPECT_EQ(pixel(image, 5, j), Color(0, 255, 0));
    }
  }
}

TEST_F(MaterialTextures, OneImageNamedTwiceIsReadOnce) {
  const Scene scene = loadWritten(threeQuads("maps/red.ppm", "maps/red.ppm", "")).scene;
  ASSERT_EQ(scene.materialTextures.size(), 1u);
  EXPECT_EQ(scene.textureOf(scene.materials[0]), scene.textureOf(scene.materials[1]));
  EXPECT_EQ(scene.textureOf(scene.materials[2]), nullptr);  // no texture of the scene's to fall back on
}

TEST_F(MaterialTextures, AMissingOneIsAWarningAtItsLineAndTheOthersStay) {
  const LoadedScene loaded = loadWritten(threeQuads("maps/red.ppm", "maps/nowhere.png", ""));
  ASSERT_EQ(loaded.warnings.size(), 1u);
  EXPECT_EQ(loaded.warnings[0].where.line, 9);  // material 2's line
  EXPECT_NE(loaded.warnings[0].message.find("texture image \"maps/nowhere.png\" could not be read"), std::string::npos)
      << loaded.warnings[0].message;
  EXPECT_NE(loaded.scene.textureOf(loaded.scene.materials[0]), nullptr);
  EXPECT_EQ(loaded.scene.textureOf(loaded.scene.materials[1]), nullptr);
}

TEST_F(MaterialTextures, SavedElsewhereTheFileStillFindsEveryImage) {
  const LoadedScene original = loadWritten(threeQuads("maps/red.ppm", "maps/blue.ppm", "green.ppm"));
  fs::create_directories(dir_ / "elsewhere" / "deeper");
  const fs::path saved = dir_ / "elsewhere" / "deeper" / "copy.xml";
  writeSceneFile(saved, original.scene);
  const LoadedScene again = loadSceneFile(saved);
  EXPECT_TRUE(again.warnings.empty()) << again.warnings.front().format();
  EXPECT_EQ(again.scene.materials[1].textureImage, "../../scene/maps/blue.ppm");
  testing::expectSameGeometry(original.scene, again.scene);
  const Image a = testing::renderChecked(original.scene, AccelKind::Packet).image;
  const Image b = testing::renderChecked(again.scene, AccelKind::Packet).image;
  EXPECT_EQ(a.rgb, b.rgb);
}

TEST_F(MaterialTextures, TheCodecCarriesNamesAndImages) {
  const Scene scene = loadWritten(threeQuads("maps/red.ppm", "maps/blue.ppm", "green.ppm")).scene;
  const Scene decoded = testing::throughTheCodec(scene);
  const SceneParameters& parameters = decoded.parameters();
  const SceneGeometry& geometry = decoded.geometry();
  EXPECT_TRUE(parameters == scene.parameters());
  EXPECT_TRUE(geometry.materialTextures == scene.materialTextures);
  EXPECT_EQ(geometry.textureImage, scene.textureImage);
}

// Emission shows with no light at all, scaled per texel by its map; it survives the writer and the codec.
TEST_F(MaterialTextures, EmissionGlowsInTheDarkScaledByItsMap) {
  writePixel(dir_ / "scene" / "maps" / "glow.ppm", 255, 0, 51);
  std::string xml = threeQuads("", "", "");
  const std::string factor = "<texturefactor>1</texturefactor>";
  std::size_t first = xml.find(factor), second = xml.find(factor, first + 1);
  xml.replace(second, factor.size(), "<emission>200 200 200</emission><emissionimage>maps/glow.ppm</emissionimage>");
  xml.replace(first, factor.size(), "<emission>10 20 30</emission>");
  const LoadedScene loaded = loadWritten(xml);
  EXPECT_TRUE(loaded.warnings.empty()) << loaded.warnings.front().format();
  const Image image = testing::renderChecked(loaded.scene, AccelKind::Packet).image;
  EXPECT_EQ(pixel(image, 0, 0), Color(10, 20, 30));   // emission alone
  EXPECT_EQ(pixel(image, 2, 0), Color(200, 0, 40));   // times the map's texel
  EXPECT_EQ(pixel(image, 4, 0), Color(0, 0, 0));      // no light, no emission
  fs::create_directories(dir_ / "elsewhere");
  writeSceneFile(dir_ / "elsewhere" / "copy.xml", loaded.scene);
  const LoadedScene again = loadSceneFile(dir_ / "elsewhere" / "copy.xml");
  EXPECT_EQ(again.scene.materials[1].emission, Color(200.0f));
  EXPECT_EQ(testing::renderChecked(again.scene, AccelKind::Packet).image.rgb, image.rgb);
  Bytes bytes;
  encodeParameters(loaded.scene.parameters(), bytes);
  std::size_t at = 0;
  EXPECT_TRUE(decodeParameters(bytes.data(), bytes.size(), at) == loaded.scene.parameters());
}

// Vertex colours multiply the ambient (and diffuse) colour, interpolated over the face; one per vertex or refused.
TEST_F(MaterialTextures, VertexColoursTintTheirFaces) {
  std::string xml = threeQuads("", "", "");
  for (std::size_t at; (at = xml.find("<texturefactor>1</texturefactor>")) != std::string::npos;)
    xml.erase(at, std::string("<texturefactor>1</texturefactor>").size());
  for (std::size_t at; (at = xml.find("<ambient>0 0 0</ambient>")) != std::string::npos;)
    xml.replace(at, std::string("<ambient>0 0 0</ambient>").size(), "<ambient>1 1 1</ambient>");
  xml.replace(xml.find("<ambientlight>0 0 0</ambientlight>"), 34, "<ambientlight>100 100 100</ambientlight>");
  std::string colours = "<colordata>";
  for (int v = 0; v < 8; ++v) colours += " 1 0.5 0.25";
  xml.replace(xml.find("  <texturedata>"), 0, colours + "</colordata>\n");
  const LoadedScene loaded = loadWritten(xml);
  EXPECT_TRUE(loaded.warnings.empty()) << loaded.warnings.front().format();
  ASSERT_EQ(loaded.scene.vertexColors.size(), 8u);
  const Image image = testing::renderChecked(loaded.scene, AccelKind::Packet).image;
  for (int i = 0; i < 6; ++i) EXPECT_EQ(pixel(image, i, 1), Color(100, 50, 25)) << i;
  fs::create_directories(dir_ / "elsewhere");
  writeSceneFile(dir_ / "elsewhere" / "copy.xml", loaded.scene);
  EXPECT_EQ(loadSceneFile(dir_ / "elsewhere" / "copy.xml").scene.vertexColors, loaded.scene.vertexColors);

  const std::string shortList = std::string(xml).replace(xml.find(colours), colours.size(), "<colordata>1 1 1 0 0 0");
  std::ofstream(dir_ / "scene" / "short.xml") << shortList;
  try {
    loadSceneFile(dir_ / "scene" / "short.xml");
    ADD_FAILURE() << "two colours for eight vertices loaded";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("<colordata> has 2 colours for 8 vertices"), std::string::npos) << e.what();
  }
}

// A metallic-roughness map sets each hit's Phong terms from the base colour and the factors times its texel
// (metallic in blue, roughness in green): exactly the image of plain materials holding those terms, and not the
// image of the averaged terms the file also holds. It survives the writer and the codec.
TEST_F(MaterialTextures, MetallicRoughnessIsShadedPerTexel) {
  writePixel(dir_ / "scene" / "maps" / "plastic.ppm", 0, 255, 0);  // metallic 0, roughness 1
  writePixel(dir_ / "scene" / "maps" / "metal.ppm", 0, 51, 255);   // metallic 1, roughness 0.2
  std::string xml = threeQuads("", "", "");
  const std::string factor = "<texturefactor>1</texturefactor>";
  const char* maps[3] = {"maps/plastic.ppm", "maps/metal.ppm", nullptr};
  for (const char* map : maps) {
    const std::size_t at = xml.find(factor);
    xml.replace(at, factor.size(),
                map ? std::string("<basecolor>0.8 0.6 0.4</basecolor><metallicroughness>1 0.5</metallicroughness>"
                                  "<metallicroughnessimage>") + map + "</metallicroughnessimage>"
                    : std::string());
  }
  for (std::size_t at; (at = xml.find("<diffuse>0 0 0</diffuse>")) != std::string::npos;)
    xml.replace(at, std::string("<diffuse>0 0 0</diffuse>").size(), "<diffuse>0.3 0.3 0.3</diffuse>");
  xml.replace(xml.find("<maxraytracedepth>0"), 19, "<maxraytracedepth>1");
  xml.replace(xml.find("<ambientlight>0 0 0</ambientlight>"), 34,
              "<ambientlight>20 20 20</ambientlight><pointlight id=\"1\"><position>0 0 1</position>"
              "<intensity>900 900 900</intensity></pointlight>");
  const LoadedScene loaded = loadWritten(xml);
  EXPECT_TRUE(loaded.warnings.empty()) << loaded.warnings.front().format();
  const Scene& scene = loaded.scene;
  ASSERT_EQ(scene.materials[1].metalRoughImage, "maps/metal.ppm");

  Scene perTexel = scene, averaged = scene;
  setPhongTerms(perTexel.materials[0], metalRoughTerms(Color(0.8f, 0.6f, 0.4f), 0.0f, 0.5f));
  setPhongTerms(perTexel.materials[1], metalRoughTerms(Color(0.8f, 0.6f, 0.4f), 1.0f, 0.5f * (51.0f / 255.0f)));
  for (Scene* s : {&perTexel, &averaged})
    for (Material& m : s->materials) m.metalRoughImage.clear();
  const Image image = testing::renderChecked(scene, AccelKind::Packet).image;
  EXPECT_EQ(image.rgb, testing::renderChecked(scene, AccelKind::Reference).image.rgb);
  EXPECT_EQ(image.rgb, testing::renderChecked(perTexel, AccelKind::Packet).image.rgb);
  EXPECT_NE(image.rgb, testing::renderChecked(averaged, AccelKind::Packet).image.rgb);

  fs::create_directories(dir_ / "elsewhere");
  writeSceneFile(dir_ / "elsewhere" / "copy.xml", scene);
  const LoadedScene again = loadSceneFile(dir_ / "elsewhere" / "copy.xml");
  EXPECT_TRUE(again.scene.parameters().materials[1].metalRoughImage == "../scene/maps/metal.ppm");
  EXPECT_EQ(testing::renderChecked(again.scene, AccelKind::Packet).image.rgb, image.rgb);
  Bytes bytes;
  encodeParameters(scene.parameters(), bytes);
  std::size_t at = 0;
  EXPECT_TRUE(decodeParameters(bytes.data(), bytes.size(), at) == scene.parameters());
}

// Factors outside 0..1 are refused at their line.
TEST_F(MaterialTextures, MetallicRoughnessFactorsAreFromZeroToOne) {
  std::string xml = threeQuads("", "", "");
  xml.replace(xml.find("<texturefactor>1</texturefactor>"), 32, "<metallicroughness>1.5 0</metallicroughness>");
  try {
    loadWritten(xml);
    ADD_FAILURE() << "a metallic factor of 1.5 loaded";
  } catch (const SceneError& e) {
    EXPECT_EQ(e.diagnostic().where.line, 8);
    EXPECT_NE(std::string(e.what()).find("must be from 0 to 1"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace rayview
