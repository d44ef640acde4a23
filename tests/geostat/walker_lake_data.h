// SPDX-License-Identifier: BSD-3-Clause
// Walker Lake (gstat's walker.csv and walker.exh.csv): 470 samples of V and the exhaustive
// 260 x 300 grid they were drawn from.
#pragma once

#include "geostat/point_set.h"
#include "tests/support/test_util.h"

namespace voxlink::geostat::test {

constexpr const char* kWalkerSamples = "geostat/gstat_csv/walker.csv";
constexpr const char* kWalkerExhaustive = "geostat/gstat_csv/walker.exh.csv";

inline PointSet walkerSamples() {
  return readPoints(testing::dataPath(kWalkerSamples), {"X", "Y", "", "V"}).value();
}

// Exhaustive V as a 260 x 300 array, x fastest, node (x, y) at index (y - 1) * 260 + x - 1.
inline std::vector<double> walkerExhaustive() {
  const PointSet all =
      readPoints(testing::dataPath(kWalkerExhaustive), {"x", "y", "", "V"}).value();
  std::vector<double> grid(260 * 300, NAN);
  for (size_t i = 0; i < all.size(); ++i) {
    const int x = int(all.coords[i][0]), y = int(all.coords[i][1]);
    grid[size_t(y - 1) * 260 + size_t(x - 1)] = all.values[i];
  }
  return grid;
}

}  // namespace voxlink::geostat::test
