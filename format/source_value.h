// SPDX-License-Identifier: BSD-3-Clause
// A decoded voxel value (stored * valueScale + valueOffset) as it comes back in the source's
// type: what dense exports write and what the converter measures its error against.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <type_traits>

namespace voxlink {

// Whole numbers are rounded (half away from zero) and clamped to T's range: an i32 2147483647
// stored as f32 decodes as 2^31, which int32 cannot hold. f32 is rounded to float within its
// finite range; f64 is unchanged.
template <class T>
double asSourceValueOf(double v) {
  if constexpr (std::is_same_v<T, double>) {
    return v;
  } else {
    constexpr double lo = double(std::numeric_limits<T>::lowest());
    constexpr double hi = double(std::numeric_limits<T>::max());
    if constexpr (std::is_integral_v<T>) return std::clamp(std::round(v), lo, hi);
    return double(static_cast<T>(std::clamp(v, lo, hi)));
  }
}

}  // namespace voxlink
