#pragma once
// The frames of a render job: a turntable (--turntable N), a batch of scenes (`rayview render A.xml B.xml -o DIR/`),
// or a CENG477 file's cameras rendered into a directory, each to its <ImageName> as the course's renderer writes
// them; which files they go to, and which of those are still to be rendered.

#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "rayview/render_job.h"

namespace rayview {

// A job whose frames cannot be named (no frame number in a turntable's output, two inputs writing the same file, ...).
class PlanError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct FrameJob {
  std::string scenePath;
  int camera = 0;  // as SceneOpenOptions::camera: 0 the file's first, else 1-based
  int frame = 0;   // of a turntable: 0 .. frames - 1; else 0
  int frames = 0;  // 0: the camera as the file gives it
  std::filesystem::path output;
};

// Frames rendered from one opening of a scene: the same file and camera.
inline bool sameSceneAndCamera(const FrameJob& a, const FrameJob& b) {
  return a.scenePath == b.scenePath && a.camera == b.camera;
}

// The job of one frame's scene: its scene, camera and output, the rest as `job` has it (what a rank is asked to
// open for the frame, and what a single process opens).
RenderJob jobForFrame(const RenderJob& job, const FrameJob& frame);

// Several frames: a turntable, more than one scene, or an output that is a directory.
bool isFrameJob(const RenderJob& job);

// Every frame the job asks for, in order; frames of one scene and camera are consecutive. Throws PlanError for an
// output that cannot name them (a turntable's needs one printf number, %d or %0Nd; a batch's is a directory, ending
// in '/') or when two frames would be written to the same file; SceneError for a CENG477 file whose cameras cannot
// be read.
std::vector<FrameJob> planFrames(const RenderJob& job);

// A frame's file is complete: it reads back as a whole image (files are written whole, so anything else is a file
// someone else left, or a crash of another program).
bool frameFileComplete(const std::filesystem::path& path);

// The frames still to render (all with `job.overwrite`), of `asked`; each output is checked before any frame is
// rendered, so nothing is written for a bad job. Returns kExitOk or the exit code (the message printed).
int pendingFrames(const RenderJob& job, std::vector<FrameJob>& pending, std::size_t& asked);

}  // namespace rayview
