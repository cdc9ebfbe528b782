#pragma once
// rayview's command line: one table of options drives parsing and --help.

#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "rayview/render_settings.h"

namespace rayview {

// Exit codes, the same for every subcommand.
inline constexpr int kExitOk = 0;
inline constexpr int kExitIoFailure = 1;
inline constexpr int kExitBadInput = 2;  // bad scene or bad arguments; nothing written

class UsageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

enum class CommandKind { Help, Version, Render, View, Bench };

struct CommandLine {
  CommandKind kind = CommandKind::View;
  std::string scenePath;   // empty: the embedded default scene
  std::string outputPath;  // render: -o
  int threads = 0;         // 0: one per hardware thread
  bool strict = false;
  bool quiet = false;
  RenderSettings settings;
  std::string scriptPath;  // view: --script FILE (automation, see docs/viewer.md)
  std::string benchName;                // bench: the benchmark to run ("tradeoff")
  std::vector<std::string> scenePaths;  // bench: every SCENE given
  std::string outputDirectory;          // bench: --out DIR
  double resolutionScale = 1.0;         // bench: --scale F
};

// Throws UsageError with a one-line message for anything it cannot take.
CommandLine parseCommandLine(const std::vector<std::string>& arguments);

std::string helpText();
std::string versionText();

}  // namespace rayview
