// SPDX-License-Identifier: BSD-3-Clause
#include "render/gl/detail/row_words.h"

namespace voxlink::render::gl {

std::vector<uint32_t> packRowWords(uint32_t n, uint64_t bricks, std::span<const uint32_t> maskWords,
                                   std::span<const uint16_t> rowStarts,
                                   std::span<const uint32_t> firstVoxels) {
  const uint64_t rows = bricks * n * n;
  std::vector<uint32_t> words(rows);
  const uint32_t rowMask = (1u << n) - 1u;
  for (uint64_t r = 0; r < rows; ++r) {
    // Row r of brick k is row r - k n^2 of it; its bits start at bit n r of MASK, since a brick's
    // n^3 bits fill whole words.
    const uint64_t bit = r * n;
    const uint32_t bits = (maskWords[bit >> 5] >> (bit & 31u)) & rowMask;
    const uint32_t base = firstVoxels.empty() ? 0u : firstVoxels[r / (uint64_t(n) * n)];
    words[r] = bits | (base + uint32_t(rowStarts[r])) << n;
  }
  return words;
}

}  // namespace voxlink::render::gl
