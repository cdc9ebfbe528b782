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

// Runs on every rank between MPI_Init_thread (MPI_THREAD_FUNNELED at least) and MPI_Finalize; returns this
// rank's exit code. Rank 0 reads the scene, deals the tiles, renders too, writes the image and the summary.
int runClusterRender(const ClusterJob& job);

}  // namespace rayview::cluster
