// SPDX-License-Identifier: BSD-3-Clause
#include "python/array_source.h"

#include <cstring>

namespace voxlink::python {

ArraySource::ArraySource(sources::VolumeInfo info, const void* data)
    : data_(static_cast<const uint8_t*>(data)) {
  info_ = std::move(info);
}

Status ArraySource::read(uint32_t z0, uint32_t count, void* dst) {
  VOXLINK_RETURN_IF_ERROR(checkSliceRange(z0, count));
  std::memcpy(dst, data_ + z0 * info_.sliceBytes(), count * info_.sliceBytes());
  return Status::ok();
}

const void* ArraySource::map(uint32_t z0, uint32_t count) {
  if (!checkSliceRange(z0, count)) return nullptr;
  return data_ + z0 * info_.sliceBytes();
}

}  // namespace voxlink::python
