// SPDX-License-Identifier: BSD-3-Clause
// Fast per-type forms of Classification::keeps(), chosen once per conversion:
//   RangeKeep  - one closed integer range (thresholds on integer data: vectorizes);
//   TableKeep  - a lookup table over every value of an 8- or 16-bit type;
//   GeneralKeep - Classification::keeps() itself (floats, wide integers, standardizing).
// All three agree with Classification::keeps() on every value (tests/convert checks it).
#pragma once

#include <cmath>
#include <cstdint>
#include <limits>
#include <type_traits>
#include <vector>

#include "convert/classification.h"

namespace voxlink::convert {

template <class T>
struct RangeKeep {
  T lo, hi;
  bool operator()(T v) const { return v >= lo && v <= hi; }
};

template <class T>
struct TableKeep {
  static_assert(sizeof(T) <= 2 && std::is_integral_v<T>);
  const uint8_t* table;  // indexed by v - numeric_limits<T>::min()
  bool operator()(T v) const {
    return table[static_cast<int32_t>(v) - static_cast<int32_t>(std::numeric_limits<T>::min())] !=
           0;
  }
};

template <class T>
struct GeneralKeep {
  const Classification* classification;
  bool operator()(T v) const { return classification->keeps(static_cast<double>(v)); }
};

// The integer range [lo, hi] of T that `interval` keeps; false when it keeps none of T.
template <class T>
bool integerRange(const tf::ValueInterval& interval, T& lo, T& hi) {
  static_assert(std::is_integral_v<T>);
  constexpr double tMin = static_cast<double>(std::numeric_limits<T>::min());
  constexpr double tMax = static_cast<double>(std::numeric_limits<T>::max());
  double l = std::ceil(interval.lo);
  if (interval.loOpen && l == interval.lo) l += 1;
  double h = std::floor(interval.hi);
  if (interval.hiOpen && h == interval.hi) h -= 1;
  l = std::max(l, tMin);
  h = std::min(h, tMax);
  if (l > h) return false;
  lo = static_cast<T>(l);
  hi = static_cast<T>(h);
  return true;
}

// Lookup table for every value of an 8- or 16-bit integer type.
template <class T>
std::vector<uint8_t> keepTable(const Classification& c) {
  const int32_t lo = std::numeric_limits<T>::min(), hi = std::numeric_limits<T>::max();
  std::vector<uint8_t> table(static_cast<size_t>(hi - lo + 1));
  for (int32_t v = lo; v <= hi; ++v) table[static_cast<size_t>(v - lo)] = c.keeps(v) ? 1 : 0;
  return table;
}

}  // namespace voxlink::convert
