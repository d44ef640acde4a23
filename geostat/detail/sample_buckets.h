// SPDX-License-Identifier: BSD-3-Clause
// Samples sorted into a uniform grid of cells, for gathering every sample within a fixed reach
// of many query points: global kriging with a compactly supported covariance (spherical) needs,
// per grid node, exactly the samples closer than the range, and a lookup of the few cells
// around the node costs far less than a scan of all n samples or a tree walk per node.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "geostat/point_set.h"

namespace voxlink::geostat {

class SampleBuckets {
 public:
  // Cells are at least `reach` wide (so a query visits at most 3 per axis), wider when that
  // would make more than about 2 cells per sample.
  SampleBuckets(const std::vector<Point3>& points, double reach);

  // Appends to `out` every sample in the cells the cube [q - reach, q + reach] touches: a
  // superset of those within `reach` of q, in a fixed order for a given q.
  void candidates(const Point3& q, std::vector<uint32_t>& out) const;

 private:
  double reach_;
  std::array<double, 3> low_{}, cell_{};
  std::array<int64_t, 3> cells_{1, 1, 1};
  std::vector<uint32_t> start_;  // per cell (x fastest), then one past the last
  std::vector<uint32_t> items_;  // sample indices, cell by cell, ascending within a cell
};

}  // namespace voxlink::geostat
