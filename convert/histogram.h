// SPDX-License-Identifier: BSD-3-Clause
// A value histogram of a whole volume, streamed slab by slab: what `voxlink stats` prints to
// help choose a threshold or a transfer function.
#pragma once

#include <cstdint>
#include <vector>

#include "convert/moments.h"
#include "sources/volume_source.h"

namespace voxlink::convert {

using sources::VolumeSource;

struct Histogram {
  double lo = 0, hi = 0;         // bin edges span [lo, hi]
  std::vector<uint64_t> counts;  // equal-width bins
  Moments moments;
  // Smallest value v such that at least `fraction` of all voxels are <= v (bin resolution).
  double quantile(double fraction) const;
};

// Two streamed passes: moments (range), then counts in `bins` bins over [min, max]; integer
// sources with a small range get one bin per value when `bins` allows.
// `progress` hears both passes as one: moments up to 0.5, counting up to 1.
Result<Histogram> measureHistogram(VolumeSource& source, uint32_t bins = 64,
                                   uint32_t slabSlices = 64, const PassProgress& progress = {});

}  // namespace voxlink::convert
