// SPDX-License-Identifier: BSD-3-Clause
// A window of consecutive z slices of a source, plus a halo of slices on either side for
// central differences. Uses the source's zero-copy mapping when it has one, else a buffer that
// keeps the halo slices it already read, so streamed sources are read exactly once per pass.
#pragma once

#include <cstdint>
#include <vector>

#include "base/check.h"
#include "sources/volume_source.h"

namespace voxlink::convert {

using sources::VolumeSource;

class SlabWindow {
 public:
  SlabWindow(VolumeSource& source, uint32_t halo);

  // Starts a new pass over the source.
  Status rewind();
  // Makes slices [z0 - halo, z1 + halo) (clipped to the volume) available. Successive loads
  // within a pass must move forward: z0 >= the previous z1 (checked).
  Status load(uint32_t z0, uint32_t z1);
  // Slice z, which must lie in the loaded range (checked in debug builds: once per row).
  const uint8_t* slice(uint32_t z) const {
    VOXLINK_DCHECK_GE(z, first_);
    VOXLINK_DCHECK_LT(z, end_);
    return base_ + (z - first_) * sliceBytes_;
  }
  // Active flags of slice z (in the loaded range), x fastest; null when the source has no
  // inactive voxels.
  const uint8_t* active(uint32_t z) const {
    return active_.empty() ? nullptr : active_.data() + (z - first_) * sliceVoxels_;
  }
  uint32_t first() const { return first_; }
  uint32_t end() const { return end_; }
  // Lets go of mapped pages of the current window.
  void release();

 private:
  VolumeSource& source_;
  uint32_t halo_;
  uint64_t sliceBytes_;
  uint32_t depth_;
  const uint8_t* base_ = nullptr;
  uint32_t first_ = 0, end_ = 0;  // loaded slices [first_, end_)
  uint32_t passEnd_ = 0;          // the last load's z1 in this pass
  bool mapped_ = false;
  std::vector<uint8_t> buffer_;
  uint64_t sliceVoxels_;
  std::vector<uint8_t> active_;  // active flags of the buffered slices (masked sources)
};

}  // namespace voxlink::convert
