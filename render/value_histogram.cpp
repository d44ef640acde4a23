// SPDX-License-Identifier: BSD-3-Clause
#include "render/value_histogram.h"

#include <algorithm>
#include <cmath>

namespace voxlink::render {

ValueHistogram valueHistogram(const format::VoxLinkFile& file, double lo, double hi,
                              uint32_t bins) {
  ValueHistogram h;
  if (!(lo < hi) || bins == 0) {
    hi = lo + 1;
    bins = std::max(bins, 1u);
  }
  h.lo = lo;
  h.hi = hi;
  h.counts.assign(bins, 0);
  const double scale = bins / (hi - lo);
  for (uint64_t i = 0; i < file.voxelCount(); ++i) {
    const double v = file.value(i);
    if (!(v >= lo && v <= hi)) continue;
    const auto b = std::min<uint64_t>(bins - 1, uint64_t((v - lo) * scale));
    ++h.counts[b];
  }
  h.maxCount = h.counts.empty() ? 0 : *std::max_element(h.counts.begin(), h.counts.end());
  return h;
}

}  // namespace voxlink::render
