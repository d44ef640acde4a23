// SPDX-License-Identifier: BSD-3-Clause
#include "convert/moments.h"

#include <algorithm>
#include <cmath>

#include "convert/detail/slab_window.h"

namespace voxlink::convert {

using sources::VolumeInfo;
using sources::VolumeSource;

namespace {

struct Accumulator {
  double n = 0, mean = 0, m2 = 0;  // count, mean, sum of squared deviations
  void merge(const Accumulator& o) {
    if (o.n == 0) return;
    const double total = n + o.n;
    const double delta = o.mean - mean;
    mean += delta * (o.n / total);
    m2 += o.m2 + delta * delta * (n * o.n / total);
    n = total;
  }
};

template <class T>
Status accumulateSlice(const T* v, const uint8_t* active, uint64_t count, uint32_t z,
                       const VolumeInfo& info, Accumulator& acc, double& lo, double& hi) {
  // Two passes over one slice: its mean first, then deviations from it. Inactive voxels (null
  // `active`: none) hold no data and are left out.
  double sum = 0, kept = 0;
  for (uint64_t i = 0; i < count; ++i) {
    if (active && !active[i]) continue;
    ++kept;
    const double x = static_cast<double>(v[i]);
    if (!std::isfinite(x))
      return makeError(ErrorCode::kNonFinite, info.path, ": data: value ", x, " at voxel (",
                       i % info.dims[0], ", ", i / info.dims[0], ", ", z, ") is not finite");
    sum += x;
  }
  if (kept == 0) return Status::ok();
  Accumulator slice;
  slice.n = kept;
  slice.mean = sum / slice.n;
  for (uint64_t i = 0; i < count; ++i) {
    if (active && !active[i]) continue;
    const double d = static_cast<double>(v[i]) - slice.mean;
    slice.m2 += d * d;
    lo = std::min(lo, static_cast<double>(v[i]));
    hi = std::max(hi, static_cast<double>(v[i]));
  }
  acc.merge(slice);
  return Status::ok();
}

}  // namespace

Result<Moments> measureMoments(VolumeSource& source, uint32_t slabSlices,
                               const PassProgress& progress) {
  const VolumeInfo& info = source.info();
  SlabWindow window(source, 0);
  VOXLINK_RETURN_IF_ERROR(window.rewind());
  Accumulator acc;
  double lo = INFINITY, hi = -INFINITY;
  slabSlices = std::max(1u, slabSlices);
  for (uint32_t z0 = 0; z0 < info.dims[2]; z0 += slabSlices) {
    const uint32_t z1 = std::min(info.dims[2], z0 + slabSlices);
    VOXLINK_RETURN_IF_ERROR(window.load(z0, z1));
    for (uint32_t z = z0; z < z1; ++z) {
      Status s = dispatchScalar(info.type, [&](auto t) {
        using T = decltype(t);
        return accumulateSlice(reinterpret_cast<const T*>(window.slice(z)), window.active(z),
                               info.sliceVoxels(), z, info, acc, lo, hi);
      });
      VOXLINK_RETURN_IF_ERROR(s);
    }
    window.release();
    if (progress) progress(double(z1) / info.dims[2], "moments");
  }
  Moments m;
  m.count = static_cast<uint64_t>(acc.n);
  m.mean = acc.mean;
  m.sigma = acc.n > 0 ? std::sqrt(acc.m2 / acc.n) : 0.0;
  m.min = lo;
  m.max = hi;
  return m;
}

}  // namespace voxlink::convert
