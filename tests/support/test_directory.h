#pragma once
// A directory of the running test's own under the system's temporary directory, made empty: named by a prefix,
// GoogleTest's random seed and the test's name, so that tests ctest runs side by side never share one.

#include <filesystem>
#include <string>

#include <gtest/gtest.h>

namespace rayview::testing {

inline std::filesystem::path freshTestDirectory(const std::string& prefix) {
  const ::testing::UnitTest& test = *::testing::UnitTest::GetInstance();
  const std::filesystem::path dir = std::filesystem::temp_directory_path() /
                                    (prefix + "_" + std::to_string(test.random_seed()) + "_" +
                                     test.current_test_info()->name());
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

}  // namespace rayview::testing
