// SPDX-License-Identifier: BSD-3-Clause
// Streaming statistics of a gridded field, fed slab by slab: mean, standard deviation, the
// fraction outside a two-sided interval, and the semivariogram along each axis at given lags
// (the last maxLag slices are kept to pair voxels across slabs).
#pragma once

#include <array>
#include <cstdint>
#include <deque>
#include <string>
#include <vector>

#include "base/error.h"

namespace voxlink::geostat {

class FieldStatistics {
 public:
  FieldStatistics(std::array<uint32_t, 3> dims, std::vector<uint32_t> lags,
                  double outsideLow = -1.96, double outsideHigh = 1.96);
  void add(uint32_t z0, uint32_t count, const double* slab);

  uint64_t count() const { return count_; }
  double mean() const;
  double sigma() const;  // population standard deviation
  double outsideFraction() const { return count_ ? double(outside_) / double(count_) : 0.0; }
  const std::vector<uint32_t>& lags() const { return lags_; }
  // Semivariogram along axis (0 x, 1 y, 2 z) at lags()[i]; NaN where no pair exists.
  double gamma(int axis, size_t lagIndex) const;
  uint64_t pairs(int axis, size_t lagIndex) const { return pairs_[axis][lagIndex]; }

 private:
  std::array<uint32_t, 3> dims_;
  std::vector<uint32_t> lags_;
  double low_, high_;
  uint64_t count_ = 0, outside_ = 0;
  double shift_ = 0;  // first value: sums of (v - shift) keep the variance accurate
  bool haveShift_ = false;
  double sum_ = 0, sumSq_ = 0;
  std::array<std::vector<double>, 3> gammaSum_;
  std::array<std::vector<uint64_t>, 3> pairs_;
  std::deque<std::vector<double>> recent_;  // previous slices, newest last
};

}  // namespace voxlink::geostat
