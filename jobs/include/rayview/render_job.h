#pragma once
// A render job as a value: where the scenes come from, how to open them, how to render, and where the images go.
// The command line makes one; the single-image, frames and batch drivers run it; under mpirun rank 0 sends it to the
// other ranks as bytes (encodeRenderJob) and every rank runs its share of the same value.

#include <cstdint>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "rayview/knobs.h"
#include "rayview/scene_open.h"

namespace rayview {

struct RenderJob {
  std::vector<std::string> scenes;  // every SCENE given; none: the embedded default scene
  SceneOpenOptions open;
  // --depth, --tri-light, ...: one per knob given (the last wins), written into the settings and, once a scene is
  // opened, into its parameters (rayview/knobs.h).
  std::vector<KnobAssignment> knobs;
  std::filesystem::path output;  // an image, a turntable's printf pattern, or a directory
  int turntableFrames = 0;       // --turntable N; 0: the scene's own camera
  bool overwrite = false;        // frames: render those whose file is already complete too
  bool quiet = false;
  int threads = 0;  // per process (per rank under mpirun); 0: one per hardware thread

  // The one scene of a single render ("" for the default scene).
  const std::string& scene() const;
};

// The settings the knobs give before a scene is opened (RenderSettings{} with the job's knobs written in).
RenderSettings renderSettingsOf(const RenderJob& job);

// Malformed bytes (another build's rank, a truncated message).
class JobCodecError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Every field, exactly; knobs by their table name. decodeRenderJob throws JobCodecError for bytes it cannot read.
std::vector<std::uint8_t> encodeRenderJob(const RenderJob& job);
RenderJob decodeRenderJob(const std::vector<std::uint8_t>& bytes);

// Runs the job in this process: one image, or frames (a turntable, a batch, a CENG477 file's cameras into a
// directory). Returns the process exit code (rayview/exit_codes.h); messages go to stderr, the summary to stdout.
int runRenderJob(const RenderJob& job);

}  // namespace rayview
