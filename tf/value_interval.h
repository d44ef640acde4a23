// SPDX-License-Identifier: BSD-3-Clause
// Sets of scalar values as unions of intervals: what a classification keeps, what a transfer
// function makes visible.
#pragma once

#include <string>
#include <vector>

namespace voxlink::tf {

struct ValueInterval {
  double lo;  // may be -infinity
  double hi;  // may be +infinity
  bool loOpen = false;
  bool hiOpen = false;

  bool contains(double v) const {
    return (loOpen ? v > lo : v >= lo) && (hiOpen ? v < hi : v <= hi);
  }
};

// True when any interval contains v.
bool anyContains(const std::vector<ValueInterval>& set, double v);
// "[60, inf)", "(-inf, -1.96) u (1.96, inf)"
std::string describeIntervals(const std::vector<ValueInterval>& set);

// Sorted, merged union.
std::vector<ValueInterval> mergeIntervals(std::vector<ValueInterval> set);
// The values not in the set (the set need not be merged).
std::vector<ValueInterval> complementIntervals(const std::vector<ValueInterval>& set);
std::vector<ValueInterval> intersectIntervals(const std::vector<ValueInterval>& a,
                                              const std::vector<ValueInterval>& b);

}  // namespace voxlink::tf
