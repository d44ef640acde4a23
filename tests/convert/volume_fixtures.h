// SPDX-License-Identifier: BSD-3-Clause
// Small dense volumes for converter tests: an in-memory VolumeSource and raw-file helpers.
#pragma once

#include <cstring>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "sources/volume_source.h"

namespace voxlink::testing {

// A dense volume held in memory. `sequential` makes it refuse backward reads like a
// compressed stream would, to exercise the converter's streaming path.
class MemorySource final : public sources::VolumeSource {
 public:
  MemorySource(sources::VolumeInfo info, std::vector<uint8_t> bytes, bool sequential);
  Status read(uint32_t z0, uint32_t count, void* dst) override;
  Status rewind() override;
  bool randomAccess() const override { return !sequential_; }
  const std::vector<uint8_t>& bytes() const { return bytes_; }

 private:
  std::vector<uint8_t> bytes_;
  bool sequential_;
  uint32_t nextZ_ = 0;
};

// A memory volume plus active flags from a function of the voxel position (like OpenVDB's
// inactive voxels).
class PartlyActiveSource final : public sources::VolumeSource {
 public:
  PartlyActiveSource(MemorySource& values, std::function<bool(uint32_t, uint32_t, uint32_t)> active)
      : values_(values), active_(std::move(active)) {
    info_ = values.info();
  }
  Status read(uint32_t z0, uint32_t count, void* dst) override {
    return values_.read(z0, count, dst);
  }
  Status rewind() override { return values_.rewind(); }
  bool randomAccess() const override { return values_.randomAccess(); }
  bool hasInactiveVoxels() const override { return true; }
  Status readActive(uint32_t z0, uint32_t count, uint8_t* dst) override {
    VOXLINK_RETURN_IF_ERROR(checkSliceRange(z0, count));
    for (uint32_t z = z0; z < z0 + count; ++z)
      for (uint32_t y = 0; y < info_.dims[1]; ++y)
        for (uint32_t x = 0; x < info_.dims[0]; ++x) *dst++ = active_(x, y, z) ? 1 : 0;
    return Status::ok();
  }
  bool active(uint32_t x, uint32_t y, uint32_t z) const { return active_(x, y, z); }

 private:
  MemorySource& values_;
  std::function<bool(uint32_t, uint32_t, uint32_t)> active_;
};

// A volume of type T filled by f(x, y, z).
template <class T>
std::unique_ptr<MemorySource> makeVolume(std::array<uint32_t, 3> dims,
                                         const std::function<T(uint32_t, uint32_t, uint32_t)>& f,
                                         bool sequential = false,
                                         std::array<double, 3> spacing = {1, 1, 1}) {
  sources::VolumeInfo info;
  info.dims = dims;
  info.type = scalarTypeOf<T>();
  info.spacing = spacing;
  info.path = "memory";
  info.format = "memory";
  std::vector<uint8_t> bytes(info.voxelCount() * sizeof(T));
  T* p = reinterpret_cast<T*>(bytes.data());
  for (uint32_t z = 0; z < dims[2]; ++z)
    for (uint32_t y = 0; y < dims[1]; ++y)
      for (uint32_t x = 0; x < dims[0]; ++x) *p++ = f(x, y, z);
  return std::make_unique<MemorySource>(info, std::move(bytes), sequential);
}

// A CT-like u8 test volume: a noisy ball with a shell and a hollow core.
std::unique_ptr<MemorySource> makeBall(std::array<uint32_t, 3> dims, bool sequential = false);

}  // namespace voxlink::testing
