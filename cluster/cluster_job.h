#pragma once
// `rayview render` on several MPI ranks: what every rank is asked to do (each parses the same command line).

#include <filesystem>
#include <string>
#include <vector>

#include "rayview/knobs.h"

namespace rayview::cluster {

struct ClusterJob {
  std::string scenePath;  // "" for the embedded default scene
  std::filesystem::path output;
  bool strict = false;
  bool quiet = false;
  int threads = 0;  // per rank; 0: one per hardware thread
  std::vector<KnobAssignment> knobs;
};

// One frame of a turntable or a batch: the scene, the turntable's frame (frames 0: the scene's own camera) and
// the file it goes to.
struct ClusterFrame {
  std::string scenePath;
  int frame = 0;
  int frames = 0;
  std::filesystem::path output;
};

// Frames under MPI: rank 0 passes the frames still to render (its plan; `planCode` not kExitOk: the plan's
// error, printed), the other ranks nothing; rank 0 broadcasts them. A batch of at least as many scenes as ranks is
// dealt by scene (scene_batch.h: each scene loaded by rank 0 and built by the one rank that renders it). Otherwise
// the scene of consecutive frames is loaded once on every rank and its frames dealt as whole frames to the ranks
// while at least as many remain as there are ranks, the last ones as tiles to all ranks (frame_units.h). Rank 0
// writes every frame. Returns this rank's exit code. Under --enable-recovery a lost rank's scenes, frames and tiles
// go to the others; scene by scene, the job ends after that scene's frames (finished frames stay written; a rerun
// renders the rest).
int runClusterFrames(const ClusterJob& job, const std::vector<ClusterFrame>& frames, int planCode);

// Runs on every rank between MPI_Init_thread (MPI_THREAD_FUNNELED at least) and MPI_Finalize; returns this
// rank's exit code. Rank 0 reads the scene, deals the tiles, renders too, writes the image and the summary.
int runClusterRender(const ClusterJob& job);

// A rank other than 0 of `mpirun -n N rayview [SCENE]`: traces the passes of the viewer on rank 0
// (cluster/viewer_farm.h) until its window closes. Returns this rank's exit code.
int runViewWorker(int threads);

}  // namespace rayview::cluster
