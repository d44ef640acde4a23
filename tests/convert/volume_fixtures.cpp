// SPDX-License-Identifier: BSD-3-Clause
#include "tests/convert/volume_fixtures.h"

#include <cmath>

namespace voxlink::testing {

MemorySource::MemorySource(sources::VolumeInfo info, std::vector<uint8_t> bytes, bool sequential)
    : bytes_(std::move(bytes)), sequential_(sequential) {
  info_ = std::move(info);
}

Status MemorySource::read(uint32_t z0, uint32_t count, void* dst) {
  if (sequential_ && z0 < nextZ_)
    return makeError(ErrorCode::kInvalidArgument, "memory: backward read of slice ", z0, " after ",
                     nextZ_);
  if (uint64_t{z0} + count > info_.dims[2])
    return makeError(ErrorCode::kInvalidArgument, "memory: read past the end");
  std::memcpy(dst, bytes_.data() + z0 * info_.sliceBytes(), count * info_.sliceBytes());
  nextZ_ = z0 + count;
  return Status::ok();
}

Status MemorySource::rewind() {
  nextZ_ = 0;
  return Status::ok();
}

std::unique_ptr<MemorySource> makeBall(std::array<uint32_t, 3> dims, bool sequential) {
  const double cx = dims[0] * 0.45, cy = dims[1] * 0.55, cz = dims[2] * 0.5;
  const double r = std::min({dims[0], dims[1], dims[2]}) * 0.4;
  return makeVolume<uint8_t>(
      dims,
      [=](uint32_t x, uint32_t y, uint32_t z) {
        const double d = std::sqrt((x - cx) * (x - cx) + (y - cy) * (y - cy) + (z - cz) * (z - cz));
        const uint32_t noise = (x * 73856093u ^ y * 19349663u ^ z * 83492791u) % 23;
        double v = d < r ? 120 + 100 * std::cos(d / r * 3.0) : 10;
        if (d < r * 0.25) v = 30;
        return static_cast<uint8_t>(std::clamp(v + noise, 0.0, 255.0));
      },
      sequential);
}

}  // namespace voxlink::testing
