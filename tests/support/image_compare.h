#pragma once
// Golden-image comparison for tests: figures a person can read, and a difference image written on failure.

#include <filesystem>
#include <string>

#include "rayview/image.h"

namespace rayview::testing {

struct ImageDifference {
  double exactPercent = 0.0;         // pixels with all channels equal
  double withinOnePercent = 0.0;     // pixels with every channel within +-1
  int maxChannelDifference = 0;
  bool sameSize = false;
  std::string summary() const;       // "99.912 % exact, 99.998 % within +-1, max difference 37"
};

ImageDifference compareImages(const Image& actual, const Image& expected);

// Writes actual, expected and a difference picture (differing pixels bright on a dark copy of `expected`)
// under the test output directory; returns the difference image's path.
std::filesystem::path writeDifferenceImages(const std::string& name, const Image& actual, const Image& expected);

// The directory tests write their artefacts into (created on demand).
std::filesystem::path testOutputDirectory();

inline std::filesystem::path sharedDirectory() { return RAYVIEW_SHARED_DIR; }
// Whether the shared folder (the course's scenes and images, the peers' scenes) is there: a test that reads it starts
// with RAYVIEW_SKIP_WITHOUT_SHARED(), so without it the test is skipped and says why instead of failing.
inline bool sharedFilesPresent() { return std::filesystem::is_directory(sharedDirectory() / "conformance" / "ceng477"); }
#define RAYVIEW_SKIP_WITHOUT_SHARED()                                                                        \
  if (!::rayview::testing::sharedFilesPresent())                                                             \
  GTEST_SKIP() << "needs " << ::rayview::testing::sharedDirectory().string()                                 \
               << " (the course's scenes and images; configure with -DRAYVIEW_SHARED_DIR=PATH)"
inline std::filesystem::path sourceDirectory() { return RAYVIEW_SOURCE_DIR; }

}  // namespace rayview::testing
