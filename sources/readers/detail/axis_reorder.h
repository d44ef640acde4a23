// SPDX-License-Identifier: BSD-3-Clause
// Grids whose axes are the coordinate axes in another order or direction (a VTK Direction of
// diag(-1, 1, 1), axis 0 along y, ...) reordered in memory so that index i, j, k runs along +x,
// +y, +z: VoxLink grids have positive spacing along x, y, z, so this keeps every voxel's world
// position. Oblique axes cannot be reordered this way.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "base/error.h"
#include "sources/readers/detail/axes.h"

namespace voxlink::sources {

struct AxisOrder {
  std::array<int, 3> worldAxis{0, 1, 2};  // world axis (0 = x) that grid axis a runs along
  std::array<bool, 3> reversed{false, false, false};  // grid axis a runs along -worldAxis[a]
  bool identity() const;
};

// The order of `axes` (columns: world vector of one step along grid axis a), or nullopt when an
// axis is oblique (off-axis components above 1e-6 of its length) or two share a world axis.
std::optional<AxisOrder> axisOrderOf(const std::array<Vec3, 3>& axes);

// `data` (dims[0] x dims[1] x dims[2] elements of `elementSize` bytes, x fastest) in the grid
// whose axis worldAxis[a] is grid axis a, each reversed one read backwards; `dims` becomes the
// new grid's. kTooLarge (naming `file`) when the copy does not fit in memory.
Result<std::vector<uint8_t>> reorderToWorldAxes(const std::vector<uint8_t>& data,
                                                std::array<uint32_t, 3>& dims, size_t elementSize,
                                                const AxisOrder& order, const std::string& file);

}  // namespace voxlink::sources
