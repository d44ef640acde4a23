// SPDX-License-Identifier: BSD-3-Clause
// What keeping one normal per voxel costs, tallied over (voxel, triangle) pairs so that tallies
// of disjoint voxel sets (threads, MPI ranks) merge into the same statistics in any order: the
// angle sum is kept in fixed point (2^-20 degree per unit), since a sum of doubles would depend
// on the order of the additions and the scene file records the mean.
#pragma once

#include <cstdint>
#include <vector>

#include "geometry/surface_voxelizer.h"

namespace voxlink::geometry {

class NormalErrorTally {
 public:
  static constexpr int kHistogramBins = 18001;  // 0.01-degree bins over 0..180

  NormalErrorTally() : histogram_(kHistogramBins, 0) {}

  // One pair at `degrees` (0..180).
  void add(double degrees);
  void countMultiTriangleVoxel() { ++multiTriangleVoxels_; }
  void merge(const NormalErrorTally& other);
  NormalErrorStats stats() const;

  // As 8-byte words (histogram, pairs, multi, sum, max's bits), to send between ranks.
  std::vector<uint64_t> words() const;
  static NormalErrorTally fromWords(const uint64_t* words);
  static constexpr size_t kWords = kHistogramBins + 4;

 private:
  std::vector<uint64_t> histogram_;
  uint64_t pairs_ = 0, multiTriangleVoxels_ = 0, sumFixed_ = 0;
  double max_ = 0.0;
};

}  // namespace voxlink::geometry
