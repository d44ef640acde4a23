// SPDX-License-Identifier: BSD-3-Clause
// CPU lookups in a VoxLink file, following the same steps as the shaders (see
// shaders/voxlink_access.glsl): brick bit -> rank -> row start -> bit rank within the row.
#pragma once

#include <array>
#include <bit>
#include <cstdint>

#include "format/brick_rows.h"
#include "format/occupied_bricks.h"
#include "format/voxlink_file.h"

namespace voxlink::format {

class VoxelLocator {
 public:
  explicit VoxelLocator(const VoxLinkFile& file);

  // Index of occupied brick `brick` (source-order linear id), or -1 when it is empty.
  int64_t occupiedIndex(uint64_t brick) const;
  // Index of the stored voxel at source coordinates (x, y, z), or -1 when none is stored.
  int64_t find(uint32_t x, uint32_t y, uint32_t z) const;

  // Calls fn(x, y, z, voxelIndex) for every stored voxel, in file order; its cost follows the
  // occupied bricks (format/occupied_bricks.h).
  template <class F>
  void forEachVoxel(F&& fn) const;

 private:
  const VoxLinkFile& file_;
  uint32_t n_;
  std::array<uint32_t, 3> grid_;
  std::array<uint32_t, 3> dims_;
  AxisFrame frame_;
  const uint32_t* occupancy_;
  const uint32_t* rank_;
  const uint32_t* base_;
  const uint16_t* rowStart_;
  const uint32_t* mask_;
};

template <class F>
void VoxelLocator::forEachVoxel(F&& fn) const {
  const uint32_t maskWords = maskWordsPerBrick(n_);
  forEachOccupiedBrick(file_.occupancyWords(), file_.gridBrickCount(), [&](uint64_t b, uint64_t k) {
    const uint32_t origin[3] = {static_cast<uint32_t>(b % grid_[0]) * n_,
                                static_cast<uint32_t>(b / grid_[0] % grid_[1]) * n_,
                                static_cast<uint32_t>(b / (uint64_t{grid_[0]} * grid_[1])) * n_};
    uint64_t voxel = base_[k];
    const uint32_t* mask = mask_ + k * maskWords;
    for (uint32_t row = 0; row < n_ * n_; ++row) {
      uint32_t bits = rowBits(mask, n_, row);
      while (bits) {
        const uint32_t depth = static_cast<uint32_t>(std::countr_zero(bits));
        bits &= bits - 1;
        uint32_t p[3];
        p[frame_.u] = origin[frame_.u] + row % n_;
        p[frame_.v] = origin[frame_.v] + row / n_;
        p[frame_.w] = origin[frame_.w] + depth;
        fn(p[0], p[1], p[2], voxel++);
      }
    }
  });
}

}  // namespace voxlink::format
