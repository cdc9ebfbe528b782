#include "rayview/frame_plan.h"

#include <cstdio>
#include <map>
#include <system_error>

#include "rayview/image.h"
#include "rayview/input_files.h"
#include "rayview/exit_codes.h"
#include "rayview/scene_source.h"

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

// The image files a directory output gets for `scene`: one per camera of a CENG477 file, each its <ImageName> (or
// the file's name and the camera's number where it has none); else the scene's name as a PNG.
std::vector<FrameJob> directoryFrames(const RenderJob& job, const std::string& scene) {
  const std::filesystem::path directory = job.output;
  const std::string stem = scene.empty() ? "default" : std::filesystem::path(scene).stem().string();
  const std::vector<std::string> names = cameraImageNames(scene, job.open);
  if (names.empty()) return {{scene, job.open.camera, 0, 0, directory / (stem + ".png")}};
  std::vector<FrameJob> frames;
  for (std::size_t k = 1; k <= names.size(); ++k) {
    if (job.open.camera != 0 && static_cast<std::size_t>(job.open.camera) != k) continue;
    const std::string& name = names[k - 1];
    const std::string file = name.empty() ? stem + "_camera" + std::to_string(k) + ".png"
                                          : std::filesystem::path(name).filename().string();
    frames.push_back({scene, static_cast<int>(k), 0, 0, directory / file});
  }
  if (frames.empty())
    throw PlanError(scene + ": camera " + std::to_string(job.open.camera) + " was asked for, but <Cameras> has " +
                    std::to_string(names.size()) + (names.size() == 1 ? " camera" : " cameras"));
  return frames;
}

// Two frames that would land on one file: the first image would be lost.
void checkOutputsApart(const std::vector<FrameJob>& frames) {
  std::map<std::filesystem::path, const FrameJob*> taken;
  for (const FrameJob& frame : frames) {
    const std::filesystem::path key = std::filesystem::absolute(frame.output).lexically_normal();
    const auto [at, fresh] = taken.emplace(key, &frame);
    if (fresh) continue;
    const FrameJob& first = *at->second;
    auto name = [](const FrameJob& f) {
      std::string text = f.scenePath.empty() ? std::string("the default scene") : f.scenePath;
      if (f.camera > 0) text += " (camera " + std::to_string(f.camera) + ")";
      return text;
    };
    throw PlanError(name(first) + " and " + name(frame) + " would both be written to " + frame.output.string() +
                    "; render them into different directories");
  }
}

std::vector<FrameJob> turntableFrames(const RenderJob& job) {
  if (job.scenes.size() > 1)
    throw PlanError("--turntable renders one scene; " + std::to_string(job.scenes.size()) + " given");
  std::size_t length = 0;
  int width = 0;
  const std::string name = job.output.string();
  const std::size_t at = numberField(name, length, width);
  if (at == std::string::npos)
    throw PlanError("--turntable needs a frame number in the output's name, e.g. -o frames/spin_%04d.png, not '" +
                    name + "'");
  std::vector<FrameJob> frames;
  for (int k = 0; k < job.turntableFrames; ++k)
    frames.push_back({job.scene(), job.open.camera, k, job.turntableFrames, numbered(name, at, length, width, k)});
  return frames;
}

}  // namespace

RenderJob jobForFrame(const RenderJob& job, const FrameJob& frame) {
  RenderJob one = job;
  one.scenes = {frame.scenePath};
  one.open.camera = frame.camera;
  one.output = frame.output;
  one.turntableFrames = 0;
  return one;
}

bool isFrameJob(const RenderJob& job) {
  return job.turntableFrames > 0 || job.scenes.size() > 1 || namesDirectory(job.output.string());
}

std::vector<FrameJob> planFrames(const RenderJob& job) {
  if (job.turntableFrames > 0) return turntableFrames(job);
  if (!namesDirectory(job.output.string()))
    throw PlanError("several scenes render into a directory: -o DIR/ (ending in '/'), not '" + job.output.string() +
                    "'");
  std::vector<FrameJob> frames;
  for (const std::string& scene : job.scenes.empty() ? std::vector<std::string>{""} : job.scenes)
    for (FrameJob& frame : directoryFrames(job, scene)) frames.push_back(std::move(frame));
  checkOutputsApart(frames);
  return frames;
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

namespace rayview {

int pendingFrames(const RenderJob& job, std::vector<FrameJob>& pending, std::size_t& asked) {
  std::vector<FrameJob> frames;
  try {
    frames = planFrames(job);
  } catch (const PlanError& error) {
    std::fprintf(stderr, "rayview: error: %s\n", error.what());
    return kExitBadInput;
  } catch (const SceneError& error) {
    std::fprintf(stderr, "%s\n", error.what());
    return kExitBadInput;
  }
  asked = frames.size();
  for (FrameJob& frame : frames) {
    if (const std::string problem = renderOutputProblem(frame.output, frame.scenePath); !problem.empty()) {
      std::fprintf(stderr, "rayview: error: %s\n", problem.c_str());
      return kExitBadInput;
    }
    if (job.overwrite || !frameFileComplete(frame.output)) pending.push_back(std::move(frame));
  }
  return kExitOk;
}

}  // namespace rayview
