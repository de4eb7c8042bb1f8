// The ranks of a distributed run: whether this process was started by an MPI launcher, its rank,
// the number of ranks, and the MPI module that carries the messages (batch/mpi_module.h).
#pragma once

#include "quadrix/batch/mpi_module.h"

namespace quadrix::batch {

// Whether this process was started by an MPI launcher (mpirun/srun set the rank's environment)
// and Quadrix was built with MPI.
bool UnderMpiLauncher();
// This process's rank and the number of ranks (0 and 1 without MPI). Load the MPI module and
// initialise MPI on first use when UnderMpiLauncher().
int MpiRank();
int MpiSize();
// The MPI module, loaded and started (MPI initialised) on first use; only when
// UnderMpiLauncher(). A launched process whose module cannot be loaded ends here with a message
// and exit status 2: going on alone, every rank would render and write every frame.
const MpiModule& Mpi();

}  // namespace quadrix::batch
