// SPDX-License-Identifier: BSD-3-Clause
#include "geostat/detail/grid_part.h"

namespace voxlink::geostat {

Status forEachRowRun(
    const std::array<uint32_t, 3>& dims, uint32_t z0, uint32_t slices, uint32_t y0, uint32_t y1,
    const std::function<Status(uint64_t firstNode, uint64_t nodes, uint64_t offset)>& run) {
  if (y0 >= y1 || slices == 0) return Status::ok();
  const uint64_t sliceNodes = uint64_t{dims[0]} * dims[1];
  if (y0 == 0 && y1 == dims[1]) return run(z0 * sliceNodes, slices * sliceNodes, 0);
  for (uint32_t k = 0; k < slices; ++k) {
    const uint64_t rowNodes = uint64_t{y1 - y0} * dims[0];
    VOXLINK_RETURN_IF_ERROR(
        run((uint64_t{z0} + k) * sliceNodes + uint64_t{y0} * dims[0], rowNodes, k * rowNodes));
  }
  return Status::ok();
}

}  // namespace voxlink::geostat
