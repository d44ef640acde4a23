// SPDX-License-Identifier: BSD-3-Clause
// The ranks this `voxlink` process runs with: MPI's when a launcher started it and the build
// has MPI (VOXLINK_MPI), else this process alone.
#pragma once

#include "base/rank_group.h"

namespace voxlink::cli {

// Starts MPI when launched by mpirun/srun; returns false when it did not (plain process).
// The group lives until endProcessRanks() (MPI_Finalize).
bool startProcessRanks(int* argc, char*** argv);
void endProcessRanks();
base::RankGroup& processRanks();

}  // namespace voxlink::cli
