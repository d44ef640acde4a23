// SPDX-License-Identifier: BSD-3-Clause
#include "geometry/voxel_grid.h"

#include <algorithm>
#include <cmath>

namespace voxlink::geometry {

Status validateGrid(const VoxelGrid& grid) {
  static constexpr const char* kAxes[] = {"x", "y", "z"};
  for (int a = 0; a < 3; ++a) {
    if (grid.dims[a] < 1 || grid.dims[a] > kMaxGridDim) {
      return makeError(ErrorCode::kInvalidArgument, "voxel grid: dims ", kAxes[a], ": ",
                       grid.dims[a], " is not in 1..", kMaxGridDim);
    }
    if (!std::isfinite(grid.origin[a])) {
      return makeError(ErrorCode::kNonFinite, "voxel grid: origin ", kAxes[a], ": ", grid.origin[a],
                       " is not finite");
    }
  }
  if (!(std::isfinite(grid.spacing) && grid.spacing > 0.0)) {
    return makeError(ErrorCode::kInvalidArgument, "voxel grid: spacing: ", grid.spacing,
                     " is not a positive finite size");
  }
  return Status::ok();
}

Result<VoxelGrid> fitGrid(const Bounds3& bounds, uint32_t resolution) {
  if (resolution < 2 || resolution > kMaxGridDim) {
    return makeError(ErrorCode::kInvalidArgument, "voxel grid: resolution: ", resolution,
                     " is not in 2..", kMaxGridDim);
  }
  if (bounds.isEmpty()) return makeError(ErrorCode::kInvalidArgument, "voxel grid: empty bounds");
  for (int a = 0; a < 3; ++a) {
    if (!std::isfinite(bounds.min[a]) || !std::isfinite(bounds.max[a]))
      return makeError(ErrorCode::kNonFinite, "voxel grid: bounds are not finite");
  }
  double longest = 0.0;
  for (int a = 0; a < 3; ++a) longest = std::max(longest, double(bounds.max[a]) - bounds.min[a]);
  VoxelGrid grid;
  grid.spacing = longest > 0.0 ? longest / (resolution - 1) : 1.0;
  for (int a = 0; a < 3; ++a) {
    const double extent = double(bounds.max[a]) - bounds.min[a];
    const double cells = longest > 0.0 ? std::ceil(extent / grid.spacing - 1e-9) : 0.0;
    grid.dims[a] = static_cast<uint32_t>(std::clamp(cells + 1.0, 1.0, double(resolution)));
    const double centre = 0.5 * (double(bounds.min[a]) + bounds.max[a]);
    grid.origin[a] = centre - 0.5 * (grid.dims[a] - 1) * grid.spacing;
  }
  return grid;
}

}  // namespace voxlink::geometry
