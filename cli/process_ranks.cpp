#include "cli/process_ranks.h"

#include <memory>

#ifdef VOXLINK_WITH_MPI
#include "mpi/mpi_rank_group.h"
#endif

namespace voxlink::cli {
namespace {
std::unique_ptr<convert::RankGroup> mpiRanks;
}

bool startProcessRanks([[maybe_unused]] int* argc, [[maybe_unused]] char*** argv) {
#ifdef VOXLINK_WITH_MPI
  if (mpi::launchedByMpi()) mpiRanks = mpi::startMpi(argc, argv);
#endif
  return mpiRanks != nullptr;
}

void endProcessRanks() { mpiRanks.reset(); }

convert::RankGroup& processRanks() { return mpiRanks ? *mpiRanks : convert::singleProcess(); }

}  // namespace voxlink::cli
