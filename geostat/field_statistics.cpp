// SPDX-License-Identifier: BSD-3-Clause
#include "geostat/field_statistics.h"

#include <algorithm>
#include <cmath>

namespace voxlink::geostat {

FieldStatistics::FieldStatistics(std::array<uint32_t, 3> dims, std::vector<uint32_t> lags,
                                 double outsideLow, double outsideHigh)
    : dims_(dims), lags_(std::move(lags)), low_(outsideLow), high_(outsideHigh) {
  for (int a = 0; a < 3; ++a) {
    gammaSum_[a].assign(lags_.size(), 0.0);
    pairs_[a].assign(lags_.size(), 0);
  }
}

void FieldStatistics::add(uint32_t /*z0*/, uint32_t count, const double* slab) {
  const uint32_t nx = dims_[0], ny = dims_[1];
  const uint64_t sliceSize = uint64_t{nx} * ny;
  const uint32_t maxLag = lags_.empty() ? 0 : *std::max_element(lags_.begin(), lags_.end());
  for (uint32_t s = 0; s < count; ++s) {
    const double* v = slab + s * sliceSize;
    if (!haveShift_) {
      shift_ = v[0];
      haveShift_ = true;
    }
    for (uint64_t i = 0; i < sliceSize; ++i) {
      const double d = v[i] - shift_;
      sum_ += d;
      sumSq_ += d * d;
      outside_ += (v[i] < low_ || v[i] > high_);
    }
    count_ += sliceSize;
    for (size_t l = 0; l < lags_.size(); ++l) {
      const uint32_t h = lags_[l];
      if (h < nx)
        for (uint32_t y = 0; y < ny; ++y)
          for (uint32_t x = 0; x + h < nx; ++x) {
            const double d = v[y * nx + x + h] - v[y * nx + x];
            gammaSum_[0][l] += 0.5 * d * d;
            ++pairs_[0][l];
          }
      if (h < ny)
        for (uint32_t y = 0; y + h < ny; ++y)
          for (uint32_t x = 0; x < nx; ++x) {
            const double d = v[(y + h) * nx + x] - v[y * nx + x];
            gammaSum_[1][l] += 0.5 * d * d;
            ++pairs_[1][l];
          }
      if (h >= 1 && h <= recent_.size()) {
        const std::vector<double>& back = recent_[recent_.size() - h];
        for (uint64_t i = 0; i < sliceSize; ++i) {
          const double d = v[i] - back[i];
          gammaSum_[2][l] += 0.5 * d * d;
        }
        pairs_[2][l] += sliceSize;
      }
    }
    if (maxLag > 0) {
      if (recent_.size() == maxLag) {
        std::vector<double> reuse = std::move(recent_.front());
        recent_.pop_front();
        reuse.assign(v, v + sliceSize);
        recent_.push_back(std::move(reuse));
      } else {
        recent_.emplace_back(v, v + sliceSize);
      }
    }
  }
}

double FieldStatistics::mean() const { return count_ ? shift_ + sum_ / double(count_) : NAN; }

double FieldStatistics::sigma() const {
  if (!count_) return NAN;
  const double m = sum_ / double(count_);
  return std::sqrt(std::max(0.0, sumSq_ / double(count_) - m * m));
}

double FieldStatistics::gamma(int axis, size_t lagIndex) const {
  const uint64_t n = pairs_[axis][lagIndex];
  return n ? gammaSum_[axis][lagIndex] / double(n) : NAN;
}

}  // namespace voxlink::geostat
