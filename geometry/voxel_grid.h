// SPDX-License-Identifier: BSD-3-Clause
// The voxel grid the voxelizers write into, with the .vxl format's convention (format/layout.h):
// voxel (i, j, k) has its centre at origin + (i, j, k) * spacing and covers
// [centre - spacing / 2, centre + spacing / 2] along each axis (cubic voxels).
//
// The voxelizers work in grid coordinates g = (p - origin) / spacing + 0.5, in which voxel i
// covers [i, i + 1] along each axis.
#pragma once

#include <array>
#include <cstdint>

#include "base/error.h"
#include "geometry/bounds.h"

namespace voxlink::geometry {

inline constexpr uint32_t kMaxGridDim = 65536;  // voxel indices fit 16 bits per axis

struct VoxelGrid {
  std::array<double, 3> origin{0.0, 0.0, 0.0};  // world position of voxel (0,0,0)'s centre
  double spacing = 1.0;                         // world size of a voxel's edge
  std::array<uint32_t, 3> dims{0, 0, 0};        // voxels along x, y, z

  std::array<double, 3> toGrid(double x, double y, double z) const {
    return {(x - origin[0]) / spacing + 0.5, (y - origin[1]) / spacing + 0.5,
            (z - origin[2]) / spacing + 0.5};
  }
  std::array<double, 3> voxelCenter(uint32_t i, uint32_t j, uint32_t k) const {
    return {origin[0] + i * spacing, origin[1] + j * spacing, origin[2] + k * spacing};
  }
};

// The slices z in [begin, end) of a grid: the part one MPI rank voxelizes
// (scene/detail/scene_ranks.h). The default covers every slice.
struct ZSlab {
  uint32_t begin = 0;
  uint32_t end = UINT32_MAX;
};

// dims in 1..kMaxGridDim, spacing finite and > 0, origin finite.
Status validateGrid(const VoxelGrid& grid);

// A grid whose longest axis has `resolution` voxels (2..kMaxGridDim) around `bounds`.
// Margin: the bounds' minimum and maximum along the longest axis lie on the centres of the first
// and last voxels (spacing = longest extent / (resolution - 1)), so half a voxel of empty-ish
// space surrounds the surface there; the other axes get ceil(extent / spacing) + 1 voxels,
// centred on the bounds (at least half a voxel of margin). Empty or non-finite bounds are an
// error; bounds of zero extent give a 1-voxel grid of spacing 1 centred on them.
Result<VoxelGrid> fitGrid(const Bounds3& bounds, uint32_t resolution);

// Key of voxel (x, y, z): sorting keys sorts voxels by (z, y, x).
inline uint64_t voxelKey(uint32_t x, uint32_t y, uint32_t z) {
  return (uint64_t(z) << 32) | (uint64_t(y) << 16) | uint64_t(x);
}
inline std::array<uint32_t, 3> voxelFromKey(uint64_t key) {
  return {uint32_t(key & 0xffff), uint32_t((key >> 16) & 0xffff), uint32_t(key >> 32)};
}

}  // namespace voxlink::geometry
