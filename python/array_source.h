// SPDX-License-Identifier: BSD-3-Clause
// A VolumeSource over a dense array someone else owns (a NumPy buffer): C order a[z][y][x],
// native byte order. Slices are served zero-copy through map(), like a mapped raw file.
#pragma once

#include "sources/volume_source.h"

namespace voxlink::python {

class ArraySource final : public sources::VolumeSource {
 public:
  // `data` must stay valid and unchanged while the source lives.
  ArraySource(sources::VolumeInfo info, const void* data);
  Status read(uint32_t z0, uint32_t count, void* dst) override;
  bool randomAccess() const override { return true; }
  const void* map(uint32_t z0, uint32_t count) override;

 private:
  const uint8_t* data_;
};

}  // namespace voxlink::python
