// SPDX-License-Identifier: BSD-3-Clause
#include "format/voxel_locator.h"

namespace voxlink::format {

VoxelLocator::VoxelLocator(const VoxLinkFile& file)
    : file_(file),
      n_(file.brickSize()),
      grid_{file.header().brickGrid[0], file.header().brickGrid[1], file.header().brickGrid[2]},
      dims_{file.header().dims[0], file.header().dims[1], file.header().dims[2]},
      frame_(axisFrame(file.predominantAxis())),
      occupancy_(file.occupancyWords().data()),
      rank_(file.rankWords().data()),
      base_(file.brickVoxelBase().data()),
      rowStart_(file.rowStarts().data()),
      mask_(file.rowMaskWords().data()) {}

int64_t VoxelLocator::occupiedIndex(uint64_t brick) const {
  const uint32_t word = occupancy_[brick >> 5];
  const uint32_t bit = static_cast<uint32_t>(brick & 31);
  if (((word >> bit) & 1u) == 0) return -1;
  return int64_t{rank_[brick >> 5]} + std::popcount(word & ((1u << bit) - 1u));
}

int64_t VoxelLocator::find(uint32_t x, uint32_t y, uint32_t z) const {
  if (x >= dims_[0] || y >= dims_[1] || z >= dims_[2]) return -1;
  const uint64_t brick = (uint64_t{z / n_} * grid_[1] + y / n_) * grid_[0] + x / n_;
  const int64_t k = occupiedIndex(brick);
  if (k < 0) return -1;
  const uint32_t local[3] = {x % n_, y % n_, z % n_};
  const uint32_t row = local[frame_.v] * n_ + local[frame_.u];
  const uint32_t bits = rowBits(mask_ + k * maskWordsPerBrick(n_), n_, row);
  const int inRow = rankInRow(bits, local[frame_.w]);
  if (inRow < 0) return -1;
  return int64_t{base_[k]} + rowStart_[k * n_ * n_ + row] + inRow;
}

}  // namespace voxlink::format
