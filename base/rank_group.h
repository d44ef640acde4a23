// SPDX-License-Identifier: BSD-3-Clause
// The processes one command runs on: this process alone (the default), or the ranks of an MPI
// job (mpi/mpi_rank_group.h). The converter, the batch runner and the scene builder talk to other
// ranks only through this interface, so they build and run without MPI.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "base/error.h"

namespace voxlink {
inline namespace base {

class RankGroup {
 public:
  virtual ~RankGroup() = default;
  virtual int rank() const = 0;
  virtual int size() const = 0;

  // Collective: every rank's `bytes` bytes at `mine`, in rank order, into `all` (size() * bytes).
  virtual void allGather(const void* mine, size_t bytes, void* all) = 0;
  // Collective: every rank's bytes, in rank order, on rank 0 (empty elsewhere).
  virtual std::vector<std::vector<uint8_t>> gatherToRoot(std::span<const uint8_t> mine) = 0;
  // Collective: `text` of rank `root` on every rank.
  virtual void broadcast(std::string& text, int root) = 0;

  // A queue of item numbers 0..items-1 handed out one at a time to whichever rank asks first.
  // startQueue and finishQueue are collective; between them a rank calls nextItem until it
  // returns nothing, and makes no other call on the group.
  virtual void startQueue(uint64_t items) = 0;
  virtual std::optional<uint64_t> nextItem() = 0;
  virtual void finishQueue() = 0;
};

// This process alone: rank 0 of 1.
RankGroup& singleProcess();

// Collective: as RankGroup::gatherToRoot for parts of any size (MPI counts bytes in int): sent
// in rounds of at most `roundBytes` over all ranks (each rank sends roundBytes / size a round).
std::vector<std::vector<uint8_t>> gatherLargeToRoot(RankGroup& group, std::span<const uint8_t> mine,
                                                    uint64_t roundBytes = uint64_t(1) << 30);

// Collective: ok on every rank when `mine` is ok on every rank; otherwise, on every rank, the
// error of the lowest failing rank, prefixed "rank R: " when there are several ranks.
Status agree(RankGroup& group, const Status& mine);

}  // namespace base
}  // namespace voxlink
