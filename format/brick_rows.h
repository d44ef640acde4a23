// SPDX-License-Identifier: BSD-3-Clause
// Relations inside one brick that writer, reader, validator and shaders share.
//
// Row r (= v*n + u) of a brick owns n bits of the brick's MASK words, starting at bit r*n
// (n divides 32, so a row never straddles two words). Bit d set means a voxel at depth d.
// The k-th set bit of a row is the row's k-th voxel: rows are contiguous in the voxel arrays,
// so the paper's next-pointer is "index + 1 while inside the row".
#pragma once

#include <bit>
#include <cstdint>

namespace voxlink::format {

// Occupancy bits of row `row` in a brick whose mask words start at `brickMask`.
inline uint32_t rowBits(const uint32_t* brickMask, uint32_t n, uint32_t row) {
  const uint32_t bit = row * n;
  const uint32_t word = brickMask[bit >> 5];
  return n == 32 ? word : (word >> (bit & 31)) & ((1u << n) - 1u);
}

// Voxel offset (relative to the row's first voxel) of depth d, or -1 when the cell is empty.
inline int rankInRow(uint32_t bits, uint32_t depth) {
  if (((bits >> depth) & 1u) == 0) return -1;
  return std::popcount(bits & ((1u << depth) - 1u));
}

// Fills rowStarts[0 .. n*n) with each row's first voxel relative to the brick; returns the
// brick's voxel count.
uint32_t rowStartsFromMasks(const uint32_t* brickMask, uint32_t n, uint16_t* rowStarts);

}  // namespace voxlink::format
