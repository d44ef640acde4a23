// SPDX-License-Identifier: BSD-3-Clause
#include "geometry/normal_error.h"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace voxlink::geometry {
namespace {
constexpr double kFixedPerDegree = 1048576.0;  // 2^20: 180 degrees x 2^20 x 2^36 pairs < 2^64
}

void NormalErrorTally::add(double degrees) {
  ++histogram_[size_t(std::min(kHistogramBins - 1, int(degrees * 100.0 + 0.5)))];
  sumFixed_ += uint64_t(std::llround(degrees * kFixedPerDegree));
  max_ = std::max(max_, degrees);
  ++pairs_;
}

void NormalErrorTally::merge(const NormalErrorTally& other) {
  for (size_t b = 0; b < histogram_.size(); ++b) histogram_[b] += other.histogram_[b];
  pairs_ += other.pairs_;
  multiTriangleVoxels_ += other.multiTriangleVoxels_;
  sumFixed_ += other.sumFixed_;
  max_ = std::max(max_, other.max_);
}

NormalErrorStats NormalErrorTally::stats() const {
  NormalErrorStats s;
  s.pairs = pairs_;
  s.multiTriangleVoxels = multiTriangleVoxels_;
  s.maxDegrees = max_;
  if (pairs_ == 0) return s;
  s.meanDegrees = double(sumFixed_) / kFixedPerDegree / double(pairs_);
  const uint64_t rank = (pairs_ * 95 + 99) / 100;  // the 95th percentile pair
  uint64_t seen = 0;
  for (int b = 0; b < kHistogramBins; ++b) {
    seen += histogram_[size_t(b)];
    if (seen >= rank) {
      s.p95Degrees = b / 100.0;
      break;
    }
  }
  return s;
}

std::vector<uint64_t> NormalErrorTally::words() const {
  std::vector<uint64_t> w(histogram_);
  uint64_t maxBits = 0;
  std::memcpy(&maxBits, &max_, sizeof maxBits);
  w.insert(w.end(), {pairs_, multiTriangleVoxels_, sumFixed_, maxBits});
  return w;
}

NormalErrorTally NormalErrorTally::fromWords(const uint64_t* words) {
  NormalErrorTally t;
  std::copy(words, words + kHistogramBins, t.histogram_.begin());
  t.pairs_ = words[kHistogramBins];
  t.multiTriangleVoxels_ = words[kHistogramBins + 1];
  t.sumFixed_ = words[kHistogramBins + 2];
  std::memcpy(&t.max_, &words[kHistogramBins + 3], sizeof t.max_);
  return t;
}

}  // namespace voxlink::geometry
