// SPDX-License-Identifier: BSD-3-Clause
#include "cli/process_ranks.h"

#include <memory>

#include "base/temp_janitor.h"
#ifdef VOXLINK_WITH_MPI
#include "mpi/mpi_rank_group.h"
#endif

namespace voxlink::cli {
namespace {
std::unique_ptr<base::RankGroup> mpiRanks;
}

bool startProcessRanks([[maybe_unused]] int* argc, [[maybe_unused]] char*** argv) {
#ifdef VOXLINK_WITH_MPI
  if (mpi::launchedByMpi()) {
    // Before MPI_Init (no threads yet): Open MPI may end this rank with _exit() when another
    // dies, and only a helper outside it can then remove rank 0's shared temporary.
    base::startTempJanitor();
    mpiRanks = mpi::startMpi(argc, argv);
  }
#endif
  return mpiRanks != nullptr;
}

void endProcessRanks() { mpiRanks.reset(); }

base::RankGroup& processRanks() { return mpiRanks ? *mpiRanks : base::singleProcess(); }

}  // namespace voxlink::cli
