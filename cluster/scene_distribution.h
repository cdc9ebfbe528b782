#pragma once
// Getting one scene onto every rank: rank 0 reads the file and broadcasts its bytes (and the texture it
// decoded), every rank loads them and applies the command line's knobs, and rank 0 checks by hash that all
// hold the same scene. Workers need no shared file system.

#include <memory>
#include <string>

#include "rayview/frame_plan.h"
#include "rayview/render_settings.h"
#include "rayview/scene.h"
#include "rayview/scene_source.h"

namespace rayview::cluster {

struct DistributedScene {
  std::shared_ptr<const Scene> scene;
  RenderSettings settings;
  double loadMs = 0.0;  // reading, broadcasting, loading and checking, on this rank
};

// Rank 0: the output checks and the scene, loaded from its file exactly as a single process loads it. Returns
// kExitOk, or the exit code with the message to print (the located load error) in `message`.
int loadSceneOnRankZero(const RenderJob& job, LoadedScene& loaded, std::string& message);

// Collective. Returns kExitOk with `out` filled, or the exit code every rank ends with; rank 0 has then printed
// the one message (a located load error, from whichever rank failed first, or a scene that differs).
int distributeScene(const RenderJob& job, int rank, int ranks, DistributedScene& out);

}  // namespace rayview::cluster
