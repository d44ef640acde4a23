// SPDX-License-Identifier: BSD-3-Clause
#include "convert/histogram.h"

#include <algorithm>
#include <cmath>

#include "convert/detail/slab_window.h"

namespace voxlink::convert {

using sources::VolumeInfo;
using sources::VolumeSource;

double Histogram::quantile(double fraction) const {
  uint64_t total = 0;
  for (uint64_t c : counts) total += c;
  const double target = fraction * static_cast<double>(total);
  uint64_t running = 0;
  const double width = counts.empty() ? 0 : (hi - lo) / counts.size();
  for (size_t b = 0; b < counts.size(); ++b) {
    running += counts[b];
    if (static_cast<double>(running) >= target) return lo + width * (b + 1);
  }
  return hi;
}

Result<Histogram> measureHistogram(VolumeSource& source, uint32_t bins, uint32_t slabSlices,
                                   const PassProgress& progress) {
  const VolumeInfo& info = source.info();
  Histogram h;
  PassProgress firstHalf;
  if (progress) firstHalf = [&](double f, const char* stage) { progress(0.5 * f, stage); };
  VOXLINK_ASSIGN_OR_RETURN(h.moments, measureMoments(source, slabSlices, firstHalf));
  bins = std::max(1u, bins);
  h.lo = h.moments.min;
  h.hi = h.moments.max;
  if (!isFloat(info.type) && h.hi - h.lo + 1 <= bins) {  // one bin per integer value
    bins = static_cast<uint32_t>(h.hi - h.lo + 1);
    h.hi = h.lo + bins;
  }
  if (h.hi <= h.lo) h.hi = h.lo + 1;
  h.counts.assign(bins, 0);
  const double scale = bins / (h.hi - h.lo);
  SlabWindow window(source, 0);
  VOXLINK_RETURN_IF_ERROR(window.rewind());
  slabSlices = std::max(1u, slabSlices);
  for (uint32_t z0 = 0; z0 < info.dims[2]; z0 += slabSlices) {
    const uint32_t z1 = std::min(info.dims[2], z0 + slabSlices);
    VOXLINK_RETURN_IF_ERROR(window.load(z0, z1));
    for (uint32_t z = z0; z < z1; ++z) {
      dispatchScalar(info.type, [&](auto t) {
        using T = decltype(t);
        const T* v = reinterpret_cast<const T*>(window.slice(z));
        const uint8_t* active = window.active(z);  // inactive voxels hold no data
        for (uint64_t i = 0; i < info.sliceVoxels(); ++i) {
          if (active && !active[i]) continue;
          const auto b = static_cast<int64_t>((static_cast<double>(v[i]) - h.lo) * scale);
          ++h.counts[static_cast<size_t>(std::clamp<int64_t>(b, 0, bins - 1))];
        }
        return 0;
      });
    }
    window.release();
    if (progress) progress(0.5 + 0.5 * double(z1) / info.dims[2], "histogram");
  }
  return h;
}

}  // namespace voxlink::convert
