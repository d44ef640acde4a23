// SPDX-License-Identifier: BSD-3-Clause
#include "sources/readers/detail/axis_reorder.h"

#include <cmath>
#include <cstring>
#include <new>

namespace voxlink::sources {

bool AxisOrder::identity() const {
  for (int a = 0; a < 3; ++a)
    if (worldAxis[a] != a || reversed[a]) return false;
  return true;
}

std::optional<AxisOrder> axisOrderOf(const std::array<Vec3, 3>& axes) {
  constexpr double kTolerance = 1e-6;  // as summarizeAxes: below it a component counts as zero
  AxisOrder order;
  std::array<bool, 3> used{false, false, false};
  for (int a = 0; a < 3; ++a) {
    const Vec3& v = axes[a];
    const double len = length(v);
    if (!(len > 0)) return std::nullopt;
    int major = 0;
    for (int c = 1; c < 3; ++c)
      if (std::fabs(v[c]) > std::fabs(v[major])) major = c;
    for (int c = 0; c < 3; ++c)
      if (c != major && std::fabs(v[c]) > kTolerance * len) return std::nullopt;
    if (used[major]) return std::nullopt;
    used[major] = true;
    order.worldAxis[a] = major;
    order.reversed[a] = v[major] < 0;
  }
  return order;
}

Result<std::vector<uint8_t>> reorderToWorldAxes(const std::vector<uint8_t>& data,
                                                std::array<uint32_t, 3>& dims, size_t elementSize,
                                                const AxisOrder& order, const std::string& file) {
  // Element strides of the grid's axes, then the stride and start of each output axis.
  const std::array<int64_t, 3> gridStride{1, int64_t{dims[0]}, int64_t{dims[0]} * dims[1]};
  std::array<uint32_t, 3> outDims{};
  std::array<int64_t, 3> step{};
  int64_t start = 0;
  for (int a = 0; a < 3; ++a) {
    const int c = order.worldAxis[a];
    outDims[c] = dims[a];
    step[c] = order.reversed[a] ? -gridStride[a] : gridStride[a];
    if (order.reversed[a]) start += int64_t{dims[a] - 1} * gridStride[a];
  }
  std::vector<uint8_t> out;
  try {
    out.resize(data.size());
  } catch (const std::bad_alloc&) {
    return makeError(ErrorCode::kTooLarge, file, ": reordering ", data.size(),
                     " bytes to the world axes needs a second copy, which does not fit in memory");
  }
  uint8_t* dst = out.data();
  for (uint32_t z = 0; z < outDims[2]; ++z) {
    for (uint32_t y = 0; y < outDims[1]; ++y) {
      int64_t at = start + int64_t{z} * step[2] + int64_t{y} * step[1];
      for (uint32_t x = 0; x < outDims[0]; ++x, at += step[0], dst += elementSize)
        std::memcpy(dst, data.data() + static_cast<size_t>(at) * elementSize, elementSize);
    }
  }
  dims = outDims;
  return out;
}

}  // namespace voxlink::sources
