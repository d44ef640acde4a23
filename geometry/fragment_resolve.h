// SPDX-License-Identifier: BSD-3-Clause
// Turns (voxel, triangle) overlaps found by any voxelizer into one fragment per voxel with the
// exact surface voxelizer's rules (surface_voxelizer.h: area-weighted normal by default, the
// largest triangle's material, the same NormalErrorStats). The GL voxelizer uses it so that both
// paths differ only in which voxels they find.
#pragma once

#include <cstdint>
#include <vector>

#include "base/error.h"
#include "geometry/surface_voxelizer.h"
#include "geometry/triangle_mesh.h"
#include "geometry/voxel_grid.h"

namespace voxlink::geometry {

struct VoxelTriangle {
  uint64_t key;       // voxelKey(x, y, z)
  uint32_t triangle;  // index into mesh.triangles / 3
};

// `pairs` in any order, each (voxel, triangle) at most once; voxels inside `grid`. Errors: a
// triangle index out of range, a voxel outside the grid, a zero-area triangle.
Result<SurfaceVoxelization> resolveVoxelTriangles(const TriangleMesh& mesh, const VoxelGrid& grid,
                                                  std::vector<VoxelTriangle> pairs,
                                                  const SurfaceVoxelizeOptions& options = {});

}  // namespace voxlink::geometry
