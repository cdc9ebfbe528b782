// `rayview render` started by mpirun becomes libexec/rayview-mpi (cluster/), the one program that links MPI: a
// render outside MPI never pays for loading libmpi (docs/scale-out.md, "Start-up").
#pragma once

#include <cstdio>
#include <cstdlib>

#include "exit_codes.h"
#include "libexec_start.h"

namespace rayview {

// The ranks mpirun started (OpenMPI's variable; PMIx's rank variable alone counts as one), 0 outside mpirun.
inline int mpiWorldSize() {
  if (const char* size = std::getenv("OMPI_COMM_WORLD_SIZE")) return std::atoi(size);
  return std::getenv("PMIX_RANK") ? 1 : 0;
}

// Under mpirun: becomes rayview-mpi, or, built without it, returns the exit code when there are several ranks
// (each would render and write the whole image). Returns -1 to carry on as a single process.
inline int handOffToMpi(char** argv) {
  const int ranks = mpiWorldSize();
  if (ranks == 0) return -1;
  execLibexecProgram("rayview-mpi", argv);
  if (ranks == 1) return -1;
  std::fprintf(stderr, "rayview: error: this rayview was built without MPI; run `rayview render` without mpirun\n");
  return kExitBadInput;
}

}  // namespace rayview
