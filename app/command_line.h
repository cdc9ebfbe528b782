#pragma once
// rayview's command line: one table of options drives parsing and --help; the render knobs among them come
// from the renderer's knob table (rayview/knobs.h).

#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "rayview/exit_codes.h"
#include "rayview/knobs.h"
#include "rayview/render_job.h"

namespace rayview {

class UsageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

enum class CommandKind { Help, Version, Render, View, Bench, Compare, Import, Export };

struct CommandLine {
  CommandKind kind = CommandKind::View;
  // What every command that reads a scene takes: the scenes (none: the embedded default), how to open them
  // (--strict, --camera, --up, --resolution, --memory), the knobs, -o, --threads, --quiet, --turntable, --overwrite.
  RenderJob job;
  std::string scriptPath;  // view: --script FILE (automation, see docs/viewer.md)
  std::string comparePath;  // view: --compare REF (a reference image, see docs/viewer.md)
  std::string benchName;                // bench: the benchmark to run ("tradeoff")
  std::vector<std::string> images;      // compare: the image, then the reference
  std::string outputDirectory;          // bench: --out DIR
  double resolutionScale = 1.0;         // bench: --scale F
  std::string diffPath;                 // compare: --diff OUT.png
  bool copyTextures = false;            // import: --copy-textures (a texture outside the model's folder too)
  double minWithin1 = 100.0;            // compare: --min-within1 P (% of pixels within 1 of the reference)
  CommandKind helpFor = CommandKind::View;  // help: whose help (`rayview render --help`: render's own)
};

// Throws UsageError with a one-line message for anything it cannot take.
CommandLine parseCommandLine(const std::vector<std::string>& arguments);

// The global help (`kind` View), or a subcommand's own: its usage line and only the options it takes.
std::string helpText(CommandKind kind = CommandKind::View);
std::string versionText();

}  // namespace rayview
