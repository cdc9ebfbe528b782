// The XML repair pass is linear in the file size, so a hostile file cannot stall a load. No assertion on time (tests
// must not): the input is large enough that the old quadratic pass (6 s for 20 000 tags, growing with the square) would
// run for about 40 minutes and exceed ctest's 600 s TIMEOUT (tests/CMakeLists.txt), while it now takes well under a
// second.

#include <gtest/gtest.h>

#include <string>

#include "rayview/scene_loader.h"

namespace rayview {
namespace {

std::string errorOf(const std::string& xml) {
  try {
    loadSceneText(xml, "deep.xml", ".");
  } catch (const SceneError& e) {
    return e.what();
  }
  ADD_FAILURE() << "the scene loaded";
  return "";
}

TEST(XmlRepairScale, DeepNestingWithMisspelledClosingTagsIsRefusedAtTheLimit) {
  constexpr int kTags = 400000;  // 7.6 MB: n nested elements, then n misspelled closing tags
  std::string xml = "<scene>\n";
  xml.reserve(20 * static_cast<std::size_t>(kTags));
  for (int i = 0; i < kTags; ++i) xml += "<material>\n";
  for (int i = 0; i < kTags; ++i) xml += "</materail>\n";
  xml += "</scene>\n";
  // The 101st level (line 101: <scene> is line 1) is beyond tinyxml2's limit of 100, which would refuse it
  // after the repair pass anyway.
  EXPECT_EQ(errorOf(xml), "deep.xml:101: error: XML syntax error: elements nested too deeply (<material> is 101 "
                          "levels deep; the limit is 100)");
}

TEST(XmlRepairScale, ManyMisspelledClosingTagsAtTheNestingLimitAreRepaired) {
  // 90 open elements under <scene>, each closing tag misspelled; repeated 2 000 times (360 000 tags): the
  // repair stays linear near the nesting limit too.
  std::string body;
  for (int i = 0; i < 90; ++i) body += "<material>";
  for (int i = 0; i < 90; ++i) body += "</materail>";
  std::string xml = "<scene>\n";
  for (int r = 0; r < 2000; ++r) xml += body + "\n";
  xml += "</scene>\n";
  const std::string message = errorOf(xml);  // repaired, then the walk finds no <camera>
  EXPECT_NE(message.find("no <camera> element"), std::string::npos) << message;
}

}  // namespace
}  // namespace rayview
