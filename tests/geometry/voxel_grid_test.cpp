// SPDX-License-Identifier: BSD-3-Clause
// fitGrid and the grid convention (voxel centres at origin + index * spacing).
#include "geometry/voxel_grid.h"

#include <gtest/gtest.h>

namespace voxlink::geometry {
namespace {

TEST(VoxelGrid, FitPutsTheLongestAxisOnVoxelCentres) {
  Bounds3 bounds;
  bounds.add(-1.0f, 2.0f, 0.0f);
  bounds.add(3.0f, 3.0f, 0.5f);
  auto grid = fitGrid(bounds, 101);
  ASSERT_TRUE(grid) << grid.message();
  EXPECT_DOUBLE_EQ(grid->spacing, 4.0 / 100.0);
  EXPECT_EQ(grid->dims[0], 101u);
  EXPECT_EQ(grid->dims[1], 26u);  // 1 / 0.04 = 25 cells + 1
  EXPECT_EQ(grid->dims[2], 14u);  // ceil(0.5 / 0.04) = 13 cells + 1
  EXPECT_DOUBLE_EQ(grid->origin[0], -1.0);
  EXPECT_NEAR(grid->voxelCenter(100, 0, 0)[0], 3.0, 1e-12);
  // The other axes are centred on the bounds, with at least half a voxel of margin.
  for (int a = 1; a < 3; ++a) {
    const double lo = grid->origin[a] - 0.5 * grid->spacing;
    const double hi = grid->origin[a] + (grid->dims[a] - 0.5) * grid->spacing;
    EXPECT_NEAR(0.5 * (lo + hi), 0.5 * (double(bounds.min[a]) + bounds.max[a]), 1e-9);
    EXPECT_LE(lo, bounds.min[a] - 0.5 * grid->spacing + 1e-9);
    EXPECT_GE(hi, bounds.max[a] + 0.5 * grid->spacing - 1e-9);
  }
  // Grid coordinates: voxel i covers [i, i + 1].
  EXPECT_NEAR(grid->toGrid(-1.0, 0, 0)[0], 0.5, 1e-12);
}

TEST(VoxelGrid, FitRejectsBadInput) {
  Bounds3 empty;
  EXPECT_FALSE(fitGrid(empty, 64));
  Bounds3 point;
  point.add(1, 2, 3);
  auto single = fitGrid(point, 64);
  ASSERT_TRUE(single);
  EXPECT_EQ(single->dims[0], 1u);
  Bounds3 box;
  box.add(0, 0, 0);
  box.add(1, 1, 1);
  EXPECT_FALSE(fitGrid(box, 1));
  EXPECT_FALSE(fitGrid(box, kMaxGridDim + 1));
  EXPECT_TRUE(fitGrid(box, kMaxGridDim));
}

TEST(VoxelGrid, KeysSortByZThenYThenX) {
  EXPECT_LT(voxelKey(65535, 65535, 0), voxelKey(0, 0, 1));
  EXPECT_LT(voxelKey(65535, 0, 3), voxelKey(0, 1, 3));
  const auto xyz = voxelFromKey(voxelKey(65535, 7, 65535));
  EXPECT_EQ(xyz[0], 65535u);
  EXPECT_EQ(xyz[1], 7u);
  EXPECT_EQ(xyz[2], 65535u);
}

}  // namespace
}  // namespace voxlink::geometry
