// `rayview render` started by mpirun becomes libexec/rayview-mpi (cluster/), the one program that links MPI: a
// render outside MPI never pays for loading libmpi (docs/scale-out.md, "Start-up").
#pragma once

#include <cstdio>
#include <cstdlib>
#include <string>

#include "rayview/exit_codes.h"
#include "libexec_start.h"

namespace rayview {

// The ranks mpirun started (OpenMPI's variable; PMIx's rank variable alone counts as one), 0 outside mpirun.
inline int mpiWorldSize() {
  if (const char* size = std::getenv("OMPI_COMM_WORLD_SIZE")) return std::atoi(size);
  return std::getenv("PMIX_RANK") ? 1 : 0;
}

// This process's rank in the job (0 outside mpirun).
inline int mpiWorldRank() {
  if (const char* rank = std::getenv("OMPI_COMM_WORLD_RANK")) return std::atoi(rank);
  if (const char* rank = std::getenv("PMIX_RANK")) return std::atoi(rank);
  return 0;
}

// Under mpirun with several ranks: becomes rayview-mpi, or, built without it, returns the exit code (each rank would
// render and write the whole image). Returns -1 to carry on as a single process: outside mpirun, and at one rank,
// where there is nothing to share and MPI's start would only cost time.
inline int handOffToMpi(char** argv) {
  if (mpiWorldSize() <= 1) return -1;
  execLibexecProgram("rayview-mpi", argv);
  std::fprintf(stderr, "rayview: error: this rayview was built without MPI; run `rayview render` without mpirun\n");
  return kExitBadInput;
}

// The viewer under mpirun with several ranks: rank 0 becomes the window (rayview-mpi-viewer), the others trace its
// passes (rayview-mpi). Returns the exit code when neither can start; -1 to open the window as a single process.
inline int handOffViewerToMpi(char** argv) {
  if (mpiWorldSize() <= 1) return -1;
  const std::string why = execLibexecProgram(mpiWorldRank() == 0 ? "rayview-mpi-viewer" : "rayview-mpi", argv);
  std::fprintf(stderr, "rayview: error: the viewer cannot run on several ranks: %s; run it without mpirun\n",
               why.c_str());
  return kExitIoFailure;
}

}  // namespace rayview
