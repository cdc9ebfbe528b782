#pragma once
// The loader tests' base scene (one element per line, so tests can name lines) and helpers to load variants
// of it. Shared by tests/loader_test.cpp and tests/loader_structure_test.cpp.

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "rayview/scene_loader.h"

namespace rayview::loader_testing {

namespace fs = std::filesystem;

// One element per line so that tests can name lines; keep the numbers in the comments right.
inline const std::string kBase =
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
inline std::string with(const std::string& from, const std::string& to, std::string text = kBase) {
  const std::size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << "test bug: '" << from << "' not in the scene";
  EXPECT_EQ(text.find(from, at + 1), std::string::npos) << "test bug: '" << from << "' is not unique";
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

inline LoadOptions strictOptions() {
  LoadOptions options;
  options.strict = true;
  return options;
}

inline LoadedScene load(const std::string& xml, const LoadOptions& options = {}) {
  return loadSceneText(xml, "t.xml", fs::temp_directory_path(), options);
}

// The full message of the error the scene raises ("" and a test failure when it loads).
inline std::string errorOf(const std::string& xml, const LoadOptions& options = {}) {
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

inline void expectError(const std::string& xml, int line, const std::string& part, const LoadOptions& options = {}) {
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


}  // namespace rayview::loader_testing
