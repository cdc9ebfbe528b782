// The regression side of a fuzz target: main() for the same LLVMFuzzerTestOneInput, built in the ordinary
// (and sanitizer) builds. Runs every file named, or found in the folders named, once; any crash, sanitizer
// report or violated property aborts. Used by ctest (fuzz_regression_*) over tests/fuzz_regressions/TARGET/.
//
//   replay_TARGET [--seconds-per-input S] FILE_OR_FOLDER...
//
// --seconds-per-input: an input taking longer fails (a hang or a quadratic pass found as a fuzzer timeout).
#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size);

namespace fs = std::filesystem;

static double secondsPerInput = 0.0;  // 0: no limit

static int runFile(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    std::fprintf(stderr, "replay: cannot read %s\n", path.c_str());
    return 1;
  }
  const std::vector<char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::printf("replay: %s (%zu bytes)\n", path.c_str(), bytes.size());
  std::fflush(stdout);
  const auto start = std::chrono::steady_clock::now();
  LLVMFuzzerTestOneInput(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size());
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (secondsPerInput > 0.0 && seconds > secondsPerInput) {
    std::fprintf(stderr, "replay: %s took %.1f s, more than the %.1f s allowed\n", path.c_str(), seconds,
                 secondsPerInput);
    return 1;
  }
  return 0;
}

int main(int argc, char** argv) {
  int first = 1;
  if (argc > 2 && std::strcmp(argv[1], "--seconds-per-input") == 0) {
    secondsPerInput = std::atof(argv[2]);
    first = 3;
  }
  if (argc <= first) {
    std::fprintf(stderr, "usage: %s [--seconds-per-input S] FILE_OR_FOLDER...\n", argv[0]);
    return 2;
  }
  int failures = 0, inputs = 0;
  for (int a = first; a < argc; ++a) {
    const fs::path arg(argv[a]);
    if (fs::is_directory(arg)) {
      std::vector<fs::path> files;
      for (const auto& entry : fs::recursive_directory_iterator(arg))
        if (entry.is_regular_file() && entry.path().filename() != "README.md") files.push_back(entry.path());
      std::sort(files.begin(), files.end());
      for (const fs::path& f : files) failures += runFile(f), ++inputs;
    } else {
      failures += runFile(arg), ++inputs;
    }
  }
  std::printf("replay: %d input(s), no crash, %d too slow or unreadable\n", inputs, failures);
  return failures == 0 ? 0 : 1;
}
