// SPDX-License-Identifier: BSD-3-Clause
// Slots of a voxel mask (format/layout.h, version 2): per 32-voxel word, the set bits before it,
// so the slot of voxel i in a payload indexed by the mask is one table read and a popcount.
// Derived when a file is opened, never stored: the file keeps only the mask.
#pragma once

#include <bit>
#include <cstdint>
#include <span>
#include <vector>

namespace voxlink::format {

class MaskRank {
 public:
  MaskRank() = default;
  explicit MaskRank(std::span<const uint32_t> mask) : mask_(mask), before_(mask.size() + 1) {
    uint32_t total = 0;
    for (size_t w = 0; w < mask.size(); ++w) {
      before_[w] = total;
      total += static_cast<uint32_t>(std::popcount(mask[w]));
    }
    before_[mask.size()] = total;
  }
  bool has(uint64_t i) const { return i / 32 < mask_.size() && ((mask_[i >> 5] >> (i & 31)) & 1u); }
  // The slot of voxel i (meaningful when has(i)).
  uint32_t slot(uint64_t i) const {
    const uint32_t below = (i & 31) == 0 ? 0u : mask_[i >> 5] << (32 - (i & 31));
    return before_[i >> 5] + static_cast<uint32_t>(std::popcount(below));
  }
  uint64_t count() const { return before_.empty() ? 0 : before_.back(); }
  // The per-word table, as the renderer uploads it (mask words + 1 entries).
  const std::vector<uint32_t>& table() const { return before_; }

 private:
  std::span<const uint32_t> mask_;
  std::vector<uint32_t> before_;
};

}  // namespace voxlink::format
