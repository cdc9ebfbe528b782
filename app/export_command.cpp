#include <cstdio>
#include <filesystem>
#include <system_error>

#include "model_commands.h"
#include "rayview/model_client.h"

namespace rayview {

int runExportCommand(const CommandLine& command) {
  std::error_code ec;
  if (std::filesystem::equivalent(command.scenePath, command.outputPath, ec)) {
    std::fprintf(stderr, "rayview: error: the output %s is the scene file; choose another name\n",
                 command.outputPath.c_str());
    return kExitBadInput;
  }
  try {
    exportSceneFile(command.scenePath, command.outputPath);
  } catch (const SceneError& error) {
    std::fprintf(stderr, "%s\n", error.what());
    return kExitBadInput;
  } catch (const ModelWriteError& error) {
    std::fprintf(stderr, "rayview: error: %s\n", error.what());
    return kExitIoFailure;
  }
  std::printf("%s: written from %s\n", command.outputPath.c_str(), command.scenePath.c_str());
  return kExitOk;
}

}  // namespace rayview
