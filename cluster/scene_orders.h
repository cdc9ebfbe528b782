#pragma once
// A batch of different scenes under MPI, dealt by scene (docs/scale-out.md, "Frames"): the runs of frames that
// share a scene, and the order rank 0 sends with a scene, as bytes. No MPI.

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "rayview/frame_plan.h"
#include "view_codec.h"

namespace rayview::cluster {

// The frames [first, end) of one scene: consecutive frames of the plan with the same scene.
struct SceneRun {
  std::size_t first = 0, end = 0;
};
std::vector<SceneRun> sceneRuns(const std::vector<FrameJob>& frames);

// One scene for one rank: the run it is (its index in the batch), its frames (turntable frame, frames), and the
// scene as loaded on rank 0 with the knobs applied (view_codec.h: geometry, then parameters and settings).
struct SceneOrder {
  std::int32_t run = 0;
  std::string scenePath;
  std::vector<std::int32_t> frames;  // pairs: frame, frames
  Bytes geometry, parameters;
};

Bytes encodeSceneOrder(const SceneOrder& order);
// Throws CodecError for malformed bytes.
SceneOrder decodeSceneOrder(const std::uint8_t* data, std::size_t size);

// What a worker sends back with each frame's RGB rows.
struct SceneResultHeader {
  std::int32_t run = 0;
  std::int32_t frame = 0;  // index into the run
  double busyMs = 0.0;     // decoding and building the scene (with its first frame), rendering the frame
  std::uint64_t hash = 0;  // sceneHash of the scene the worker decoded: rank 0 compares it with its own
  std::uint64_t camera = 0, shadow = 0, reflection = 0;
};

}  // namespace rayview::cluster
