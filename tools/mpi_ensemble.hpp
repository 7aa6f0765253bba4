#pragma once
// rockdd mc under mpirun: rank 0 owns the ensemble folder (lock, manifest, mc.csv) and runs
// realizations like every other rank; each rank asks rank 0 for its next seed when it has a
// free job, and sends rank 0 the row of each realization it finished.
#include "engine/monte_carlo/monte_carlo.hpp"
#include "tools/monte_carlo_command.hpp"

namespace rockdd::cli {

/// True when this process was started by an MPI launcher (mpirun, mpiexec, srun): the
/// environment names its rank. A plain `rockdd mc` never initializes MPI.
bool launched_by_mpi();

/// rockdd mc across the ranks of MPI_COMM_WORLD; the exit status of monte_carlo() on rank 0,
/// and on the others 0, or 2 when the ensemble could not start.
int mpi_monte_carlo(MonteCarloOptions options);

}  // namespace rockdd::cli
