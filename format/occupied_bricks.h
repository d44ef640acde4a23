// SPDX-License-Identifier: BSD-3-Clause
// A walk over the occupied bricks of a file's occupancy bits (BOCC), in brick order, that skips
// whole zero words: a sparse file's cost follows its occupied bricks, not its grid (one voxel in
// a 65536 x 32768 x 1 grid of 4-voxel bricks is 134 million bits, 4 million words).
#pragma once

#include <bit>
#include <cstdint>
#include <span>

namespace voxlink::format {

// Calls fn(b, k) for every set bit b < `bricks` of `occupancy` (the brick's source-order id),
// k counting the occupied bricks from 0.
template <class F>
void forEachOccupiedBrick(std::span<const uint32_t> occupancy, uint64_t bricks, F&& fn) {
  uint64_t k = 0;
  for (uint64_t w = 0; w < occupancy.size(); ++w) {
    for (uint32_t bits = occupancy[w]; bits != 0; bits &= bits - 1) {
      const uint64_t b = w * 32 + static_cast<uint64_t>(std::countr_zero(bits));
      if (b >= bricks) return;
      fn(b, k++);
    }
  }
}

}  // namespace voxlink::format
