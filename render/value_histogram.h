// SPDX-License-Identifier: BSD-3-Clause
// Counts of a file's stored values (in source units) over equal bins: what the transfer
// function editor draws its control points over.
#pragma once

#include <cstdint>
#include <vector>

#include "format/voxlink_file.h"

namespace voxlink::render {

struct ValueHistogram {
  double lo = 0, hi = 1;         // value range the bins cover
  std::vector<uint64_t> counts;  // bins of width (hi - lo) / counts.size()
  uint64_t maxCount = 0;
};

// Bins over [lo, hi]; values outside are not counted.
ValueHistogram valueHistogram(const format::VoxLinkFile& file, double lo, double hi, uint32_t bins);

}  // namespace voxlink::render
