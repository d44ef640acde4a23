// SPDX-License-Identifier: BSD-3-Clause
#include "render/gl/detail/row_words.h"

#include <bit>

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

ApronRows packApronRows(uint32_t n, uint64_t bricks, std::span<const uint32_t> maskWords,
                        std::span<const uint16_t> rowStarts, std::span<const uint32_t> firstVoxels,
                        std::span<const uint32_t> voxelWords,
                        std::span<const uint32_t> nextAlongW) {
  const uint64_t rowsPerBrick = uint64_t(n) * n;
  const uint32_t rowMask = (1u << n) - 1u;
  auto bitsOf = [&](uint64_t r) { return (maskWords[(r * n) >> 5] >> ((r * n) & 31u)) & rowMask; };
  ApronRows out;
  out.rowWords.resize(bricks * rowsPerBrick);
  out.voxelWords.reserve(voxelWords.size() + voxelWords.size() / n);
  for (uint64_t k = 0; k < bricks; ++k)
    for (uint64_t row = 0; row < rowsPerBrick; ++row) {
      const uint64_t r = k * rowsPerBrick + row;
      const uint32_t bits = bitsOf(r);
      const uint32_t start = uint32_t(out.voxelWords.size());
      const uint32_t first = firstVoxels[k] + rowStarts[r];
      const uint32_t count = uint32_t(std::popcount(bits));
      out.voxelWords.insert(out.voxelWords.end(), voxelWords.begin() + first,
                            voxelWords.begin() + first + count);
      uint32_t apron = 0;
      const uint32_t next = nextAlongW[k];
      if (next != 0xFFFFFFFFu) {
        const uint64_t nr = next * rowsPerBrick + row;
        if ((bitsOf(nr) & 1u) != 0u) {
          apron = 1;
          out.voxelWords.push_back(voxelWords[firstVoxels[next] + rowStarts[nr]]);
        }
      }
      out.rowWords[r] = bits | apron << n | start << (n + 1);
    }
  return out;
}

}  // namespace voxlink::render::gl
