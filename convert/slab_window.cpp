// SPDX-License-Identifier: BSD-3-Clause
#include "convert/detail/slab_window.h"

#include <algorithm>
#include <cstring>

namespace voxlink::convert {

using sources::VolumeSource;

SlabWindow::SlabWindow(VolumeSource& source, uint32_t halo)
    : source_(source),
      halo_(halo),
      sliceBytes_(source.info().sliceBytes()),
      depth_(source.info().dims[2]),
      sliceVoxels_(source.info().sliceVoxels()) {}

Status SlabWindow::rewind() {
  release();
  first_ = end_ = passEnd_ = 0;
  base_ = nullptr;
  buffer_.clear();
  active_.clear();
  return source_.rewind();
}

Status SlabWindow::load(uint32_t z0, uint32_t z1) {
  VOXLINK_CHECK_GE(z0, passEnd_);  // forward only: the kept slices assume it
  VOXLINK_CHECK_LE(z0, z1);
  VOXLINK_CHECK_LE(z1, depth_);
  passEnd_ = z1;
  const uint32_t first = z0 > halo_ ? z0 - halo_ : 0;
  const uint32_t end = std::min(depth_, z1 + halo_);
  // Sources with inactive voxels give values and active flags in one read (one walk of an
  // OpenVDB tree); they are buffered like streamed sources.
  const bool masked = source_.hasInactiveVoxels();
  if (const void* p = masked ? nullptr : source_.map(first, end - first)) {
    release();
    base_ = static_cast<const uint8_t*>(p);
    mapped_ = true;
    first_ = first;
    end_ = end;
    return Status::ok();
  }
  // Keep the slices already read that the new window still needs, read only the rest.
  const uint32_t keepFrom = std::max(first, first_);
  uint32_t kept = (!mapped_ && base_ && first >= first_ && end_ > keepFrom) ? end_ - keepFrom : 0;
  kept = std::min(kept, end - first);
  mapped_ = false;
  if (kept > 0) {
    std::memmove(buffer_.data(), buffer_.data() + (keepFrom - first_) * sliceBytes_,
                 kept * sliceBytes_);
    if (masked)
      std::memmove(active_.data(), active_.data() + (keepFrom - first_) * sliceVoxels_,
                   kept * sliceVoxels_);
  }
  const uint64_t slices = end - first;
  if (buffer_.size() < slices * sliceBytes_) buffer_.resize(slices * sliceBytes_);
  if (masked && active_.size() < slices * sliceVoxels_) active_.resize(slices * sliceVoxels_);
  const uint32_t readFrom = first + kept;
  if (end > readFrom) {
    uint8_t* values = buffer_.data() + uint64_t{kept} * sliceBytes_;
    VOXLINK_RETURN_IF_ERROR(
        masked ? source_.readWithActive(readFrom, end - readFrom, values,
                                        active_.data() + uint64_t{kept} * sliceVoxels_)
               : source_.read(readFrom, end - readFrom, values));
  }
  base_ = buffer_.data();
  first_ = first;
  end_ = end;
  return Status::ok();
}

void SlabWindow::release() {
  if (mapped_ && end_ > first_) source_.unmap(first_, end_ - first_);
  mapped_ = false;
}

}  // namespace voxlink::convert
