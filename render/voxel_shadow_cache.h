// SPDX-License-Identifier: BSD-3-Clause
// The reference renderer's store for `ShadowRays::kPerVoxel` (docs/shadows.md): one float64
// transmittance per voxel of a dense volume, computed by the first ray that needs it. Rows
// render in parallel: two threads that miss the same voxel both compute it, and since the value
// is deterministic both store the same bits. The GL renderer's counterpart is
// shaders/shadow_cache.glsl (8 bits per stored voxel, per frame).
#pragma once

#include <atomic>
#include <bit>
#include <cstdint>
#include <memory>

namespace voxlink::render {

class VoxelShadowCache {
 public:
  explicit VoxelShadowCache(uint64_t voxels) : bits_(new std::atomic<uint64_t>[voxels]()) {}

  // Voxel `index`'s transmittance: compute() on the first request, the stored value after.
  template <class Compute>
  double get(uint64_t index, const Compute& compute) {
    // 0 marks "not yet"; a transmittance in [0, 1] is stored as its bits + 1 (never 0).
    const uint64_t stored = bits_[index].load(std::memory_order_relaxed);
    if (stored != 0) return std::bit_cast<double>(stored - 1);
    const double t = compute();
    bits_[index].store(std::bit_cast<uint64_t>(t) + 1, std::memory_order_relaxed);
    return t;
  }

 private:
  std::unique_ptr<std::atomic<uint64_t>[]> bits_;
};

}  // namespace voxlink::render
