// SPDX-License-Identifier: BSD-3-Clause
// The grid files of `voxlink krige` and `voxlink grf` (geostat/grid_writer.h), written by every
// rank of an MPI job together (docs/scale.md): rank 0 creates each temporary and tells the
// others its name, every rank writes its nodes at their places, and rank 0 writes the headers
// and renames the files once every rank has written. With one process, the same steps alone.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "base/rank_group.h"
#include "geostat/grid_writer.h"

namespace voxlink::cli {

class SharedGrids {
 public:
  // Collective: every rank gets a writer for each of `paths`, or every rank the error of the
  // lowest failing one (no temporary left).
  static Result<SharedGrids> open(base::RankGroup& ranks, const std::vector<std::string>& paths,
                                  const geostat::GridFileInfo& info);

  geostat::GridWriter& operator[](size_t i) { return *writers_[i]; }

  // Collective, after this rank wrote its nodes (`mine`: whether it did): the grids are put in
  // place only when every rank succeeded; every rank gets the same status.
  Status finish(const Status& mine);

 private:
  base::RankGroup* ranks_ = nullptr;
  std::vector<std::unique_ptr<geostat::GridWriter>> writers_;
};

}  // namespace voxlink::cli
