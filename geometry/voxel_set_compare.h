// SPDX-License-Identifier: BSD-3-Clause
// How a voxelization differs from a reference one (the GL path against the exact path): voxels
// it misses, voxels it adds, and the angle between the two normals on the voxels both hold.
#pragma once

#include <cstdint>
#include <vector>

#include "geometry/surface_voxelizer.h"

namespace voxlink::geometry {

struct VoxelSetComparison {
  uint64_t reference = 0, candidate = 0;
  uint64_t common = 0;
  uint64_t missing = 0;             // in the reference, not in the candidate
  uint64_t extra = 0;               // in the candidate, not in the reference
  uint64_t materialMismatches = 0;  // common voxels whose materials differ
  double normalMeanDegrees = 0.0, normalP95Degrees = 0.0, normalMaxDegrees = 0.0;  // common
};

// Both lists sorted by (z, y, x) with one entry per voxel, as the voxelizers return them.
VoxelSetComparison compareSurfaceVoxels(const std::vector<SurfaceVoxel>& reference,
                                        const std::vector<SurfaceVoxel>& candidate);

}  // namespace voxlink::geometry
