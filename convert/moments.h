// SPDX-License-Identifier: BSD-3-Clause
// Mean, standard deviation and range of a whole volume, streamed slab by slab: what
// `--keep-outside LO,HI --standardize` needs to classify z = (v - mean) / sigma.
#pragma once

#include <cstdint>
#include <functional>

#include "sources/volume_source.h"

namespace voxlink::convert {

using sources::VolumeSource;

struct Moments {
  uint64_t count = 0;
  double mean = 0;
  double sigma = 0;  // population standard deviation
  double min = 0, max = 0;
};

// Per-slice sums in double merged with Chan et al.'s pairwise update, in slice order: stable
// for large offsets (UTM-like means) and deterministic. Fails on NaN/Inf, naming the voxel.
// `progress` (may be empty) hears the fraction of the pass done after each slab, for a CLI's bar.
using PassProgress = std::function<void(double fraction, const char* stage)>;
Result<Moments> measureMoments(VolumeSource& source, uint32_t slabSlices = 64,
                               const PassProgress& progress = {});

}  // namespace voxlink::convert
