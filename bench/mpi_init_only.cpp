// OpenMPI's own start and end for a job, with no rayview in it: what bench/mpi_bench.py sets against a render's
// fixed cost under mpirun.
#include <mpi.h>

int main(int argc, char** argv) {
  MPI_Init(&argc, &argv);
  MPI_Finalize();
  return 0;
}
