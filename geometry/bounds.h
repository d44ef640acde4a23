// SPDX-License-Identifier: BSD-3-Clause
// An axis-aligned box in world units; empty until a point is added.
#pragma once

#include <algorithm>
#include <array>
#include <limits>

namespace voxlink::geometry {

struct Bounds3 {
  std::array<float, 3> min{std::numeric_limits<float>::infinity(),
                           std::numeric_limits<float>::infinity(),
                           std::numeric_limits<float>::infinity()};
  std::array<float, 3> max{-std::numeric_limits<float>::infinity(),
                           -std::numeric_limits<float>::infinity(),
                           -std::numeric_limits<float>::infinity()};

  bool isEmpty() const { return !(min[0] <= max[0] && min[1] <= max[1] && min[2] <= max[2]); }
  void add(float x, float y, float z) {
    min = {std::min(min[0], x), std::min(min[1], y), std::min(min[2], z)};
    max = {std::max(max[0], x), std::max(max[1], y), std::max(max[2], z)};
  }
  void add(const Bounds3& other) {
    if (other.isEmpty()) return;
    add(other.min[0], other.min[1], other.min[2]);
    add(other.max[0], other.max[1], other.max[2]);
  }
};

}  // namespace voxlink::geometry
