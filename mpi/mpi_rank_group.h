// SPDX-License-Identifier: BSD-3-Clause
// The ranks of an MPI job as a base::RankGroup. MPI is initialized only when a launcher
// (mpirun, mpiexec, srun) started this process, so a plain `voxlink` never touches MPI.
#pragma once

#include <memory>

#include "base/rank_group.h"

namespace voxlink::mpi {

// True when the environment says a launcher started this process (Open MPI, PMI/PMIx, Slurm).
bool launchedByMpi();

// Initializes MPI (thread level serialized) and gives the world communicator as a group;
// MPI_Finalize runs when it is destroyed. Call once, before any thread starts.
std::unique_ptr<base::RankGroup> startMpi(int* argc, char*** argv);

}  // namespace voxlink::mpi
