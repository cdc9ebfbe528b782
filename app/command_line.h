#pragma once
// rayview's command line: one table of options drives parsing and --help; the render knobs among them come
// from the renderer's knob table (rayview/knobs.h).

#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "exit_codes.h"
#include "rayview/knobs.h"
#include "rayview/lean_memory.h"
#include "rayview/model_options.h"

namespace rayview {

class UsageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

enum class CommandKind { Help, Version, Render, View, Bench, Compare, Import, Export };

struct CommandLine {
  CommandKind kind = CommandKind::View;
  std::string scenePath;   // empty: the embedded default scene
  std::string outputPath;  // render: -o
  int threads = 0;         // 0: one per hardware thread
  bool strict = false;
  bool quiet = false;
  MemoryUse memory = MemoryUse::Auto;  // render: --memory (rayview/lean_memory.h)
  int camera = 0;          // render: --camera N, which camera of a CENG477 file's <Cameras> (0: the first)
  // --depth, --tri-light, ...: one per knob given (the last wins), written into the render settings at once
  // and into the scene's parameters once it is loaded (see knobs.h).
  std::vector<KnobAssignment> knobs;
  int turntableFrames = 0;  // render: --turntable N (0: one image of the scene's own camera)
  bool overwrite = false;   // render, frames: render every frame, even those whose file is already complete
  std::string scriptPath;  // view: --script FILE (automation, see docs/viewer.md)
  std::string comparePath;  // view: --compare REF (a reference image, see docs/viewer.md)
  std::string benchName;                // bench: the benchmark to run ("tradeoff")
  std::vector<std::string> scenePaths;  // bench, and render of several scenes: every SCENE given
  std::string outputDirectory;          // bench: --out DIR
  double resolutionScale = 1.0;         // bench: --scale F
  std::string diffPath;                 // compare: --diff OUT.png
  double minWithin1 = 100.0;            // compare: --min-within1 P (% of pixels within 1 of the reference)
  ModelImportOptions model;             // import, and a model rendered or viewed: --up, --resolution, --camera, --lights
  CommandKind helpFor = CommandKind::View;  // help: whose help (`rayview render --help`: render's own)
};

// The default settings with the knobs given on the command line.
RenderSettings renderSettingsOf(const CommandLine& command);

// Throws UsageError with a one-line message for anything it cannot take.
CommandLine parseCommandLine(const std::vector<std::string>& arguments);

// The global help (`kind` View), or a subcommand's own: its usage line and only the options it takes.
std::string helpText(CommandKind kind = CommandKind::View);
// "1 point light", "2 point lights".
std::string counted(std::size_t count, const std::string& singular);
std::string versionText();

}  // namespace rayview
