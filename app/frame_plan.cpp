#include "frame_plan.h"

#include <cstdio>
#include <system_error>

#include "rayview/image.h"
#include "rayview/input_files.h"

namespace rayview {
namespace {

// The printf number in a turntable's output name: its position and width ("%04d": 4), or npos.
std::size_t numberField(const std::string& name, std::size_t& length, int& width) {
  for (std::size_t at = name.find('%'); at != std::string::npos; at = name.find('%', at + 1)) {
    std::size_t end = at + 1;
    width = 0;
    if (end < name.size() && name[end] == '0') ++end;
    while (end < name.size() && name[end] >= '0' && name[end] <= '9') width = width * 10 + (name[end++] - '0');
    if (end < name.size() && name[end] == 'd' && width <= 12) {
      length = end + 1 - at;
      return at;
    }
  }
  return std::string::npos;
}

std::string numbered(const std::string& name, std::size_t at, std::size_t length, int width, int frame) {
  char digits[32];
  std::snprintf(digits, sizeof digits, "%0*d", width, frame);
  return name.substr(0, at) + digits + name.substr(at + length);
}

bool namesDirectory(const std::string& output) {
  std::error_code error;
  return !output.empty() && (output.back() == '/' || std::filesystem::is_directory(output, error));
}

}  // namespace

bool isFrameCommand(const CommandLine& command) {
  return command.turntableFrames > 0 || command.scenePaths.size() > 1 || namesDirectory(command.outputPath);
}

std::vector<FrameJob> planFrames(const CommandLine& command) {
  std::vector<FrameJob> jobs;
  if (command.turntableFrames > 0) {
    if (command.scenePaths.size() > 1) throw UsageError("--turntable renders one scene; " + std::to_string(command.scenePaths.size()) + " given");
    std::size_t length = 0;
    int width = 0;
    const std::string name = command.outputPath;
    const std::size_t at = numberField(name, length, width);
    if (at == std::string::npos)
      throw UsageError("--turntable needs a frame number in the output's name, e.g. -o frames/spin_%04d.png, not '" +
                       name + "'");
    for (int k = 0; k < command.turntableFrames; ++k)
      jobs.push_back({command.scenePath, k, command.turntableFrames, numbered(name, at, length, width, k)});
    return jobs;
  }
  if (!namesDirectory(command.outputPath))
    throw UsageError("several scenes render into a directory: -o DIR/ (ending in '/'), not '" + command.outputPath + "'");
  for (const std::string& scene : command.scenePaths)
    jobs.push_back({scene, 0, 0, std::filesystem::path(command.outputPath) / (std::filesystem::path(scene).stem().string() + ".png")});
  if (command.scenePaths.empty())
    jobs.push_back({"", 0, 0, std::filesystem::path(command.outputPath) / "default.png"});
  return jobs;
}

bool frameFileComplete(const std::filesystem::path& path) {
  std::error_code error;
  if (!std::filesystem::is_regular_file(path, error)) return false;
  // Read only to see whether it is whole: an output this command may replace, not one of its inputs.
  bool complete = false;
  try {
    const Image image = readImageFile(path);
    complete = image.width > 0 && image.height > 0;
  } catch (const ImageIoError&) {
  }
  forgetInput(path);
  return complete;
}

}  // namespace rayview
