#include <cstdio>
#include <filesystem>
#include <system_error>

#include "model_commands.h"
#include "rayview/model_client.h"
#include "rayview/scene_open.h"

namespace rayview {

// Any input the other commands open, opened the same way (a CENG477 file's camera, a model's up axis), then written
// by the import worker, which holds the exporters.
int runExportCommand(const CommandLine& command) {
  const std::string& input = command.job.scene();
  const std::filesystem::path& output = command.job.output;
  std::error_code ec;
  if (std::filesystem::equivalent(input, output, ec)) {
    std::fprintf(stderr, "rayview: error: the output %s is the scene file; choose another name\n", output.c_str());
    return kExitBadInput;
  }
  try {
    const LoadedScene loaded = openScene(input, command.job.open);
    for (const Diagnostic& warning : loaded.warnings) std::fprintf(stderr, "%s\n", warning.format().c_str());
    exportOpenedScene(loaded.scene, output);
  } catch (const SceneError& error) {
    std::fprintf(stderr, "%s\n", error.what());
    return kExitBadInput;
  } catch (const ModelWriteError& error) {
    std::fprintf(stderr, "rayview: error: %s\n", error.what());
    return kExitIoFailure;
  }
  std::printf("%s: written from %s\n", output.c_str(), input.c_str());
  return kExitOk;
}

}  // namespace rayview
