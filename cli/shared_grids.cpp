// SPDX-License-Identifier: BSD-3-Clause
#include "cli/shared_grids.h"

#include <sstream>

namespace voxlink::cli {

Result<SharedGrids> SharedGrids::open(base::RankGroup& ranks, const std::vector<std::string>& paths,
                                      const geostat::GridFileInfo& info) {
  SharedGrids grids;
  grids.ranks_ = &ranks;
  Status created;
  std::string tempNames;  // one a line, in the order of `paths`
  if (ranks.rank() == 0)
    for (const std::string& path : paths) {
      auto writer = geostat::GridWriter::create(path, info);
      if (!writer) {
        created = writer.status();
        break;
      }
      tempNames += (*writer)->tempPath() + "\n";
      grids.writers_.push_back(std::move(*writer));
    }
  VOXLINK_RETURN_IF_ERROR(base::agree(ranks, created));
  if (ranks.size() == 1) return grids;
  ranks.broadcast(tempNames, 0);
  Status attached;
  if (ranks.rank() != 0) {
    std::istringstream names(tempNames);
    std::string tempPath;
    for (const std::string& path : paths) {
      std::getline(names, tempPath);
      auto writer = geostat::GridWriter::attach(path, tempPath, info);
      if (!writer) {
        attached = writer.status();
        break;
      }
      grids.writers_.push_back(std::move(*writer));
    }
  }
  VOXLINK_RETURN_IF_ERROR(base::agree(ranks, attached));  // rank 0's writers remove them
  return grids;
}

Status SharedGrids::finish(const Status& mine) {
  base::RankGroup& ranks = *ranks_;
  Status wrote = mine;
  if (ranks.rank() != 0)
    for (auto& writer : writers_)
      if (wrote) wrote = writer->close();
  VOXLINK_RETURN_IF_ERROR(base::agree(ranks, wrote));
  // Every node of every grid written once: the sums must be the grids' sizes.
  const size_t grids = writers_.size();
  std::vector<uint64_t> counts(grids), all(grids * static_cast<size_t>(ranks.size()));
  for (size_t i = 0; i < grids; ++i) counts[i] = writers_[i]->nodesWritten();
  ranks.allGather(counts.data(), grids * sizeof(uint64_t), all.data());
  Status committed;
  if (ranks.rank() == 0)
    for (size_t i = 0; i < grids && committed; ++i) {
      uint64_t total = 0;
      for (int r = 0; r < ranks.size(); ++r) total += all[static_cast<size_t>(r) * grids + i];
      committed = writers_[i]->finish(total);
    }
  return base::agree(ranks, committed);
}

}  // namespace voxlink::cli
