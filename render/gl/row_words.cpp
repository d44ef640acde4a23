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

namespace {

// Bit of row j's mask bits (j < 3: in word 0) and of its apron bit (word 0 for j < 3, word 1 for
// row 3) in a row group.
uint32_t groupMaskBit(uint32_t n, uint32_t j) { return j < 3 ? j * n : 0u; }
uint32_t groupApronBit(uint32_t n, uint32_t j) { return j < 3 ? 3 * n + j : n; }

}  // namespace

ApronRows packApronRows(uint32_t n, uint64_t bricks, std::span<const uint32_t> maskWords,
                        std::span<const uint16_t> rowStarts, std::span<const uint32_t> firstVoxels,
                        std::span<const uint32_t> voxelWords,
                        std::span<const uint32_t> nextAlongW) {
  const uint64_t rowsPerBrick = uint64_t(n) * n;
  const uint32_t rowMask = (1u << n) - 1u;
  auto bitsOf = [&](uint64_t r) { return (maskWords[(r * n) >> 5] >> ((r * n) & 31u)) & rowMask; };
  ApronRows out;
  out.rowGroups.assign(bricks * rowsPerBrick / kRowsPerGroup * 2, 0u);
  out.voxelWords.reserve(voxelWords.size() + voxelWords.size() / n);
  for (uint64_t k = 0; k < bricks; ++k)
    for (uint64_t row = 0; row < rowsPerBrick; ++row) {
      const uint64_t r = k * rowsPerBrick + row;
      uint32_t* group = &out.rowGroups[r / kRowsPerGroup * 2];
      const uint32_t j = uint32_t(r % kRowsPerGroup);
      if (j == 0) group[1] = uint32_t(out.voxelWords.size()) << (n + 1);
      const uint32_t bits = bitsOf(r);
      const uint32_t first = firstVoxels[k] + rowStarts[r];
      const uint32_t count = uint32_t(std::popcount(bits));
      out.voxelWords.insert(out.voxelWords.end(), voxelWords.begin() + first,
                            voxelWords.begin() + first + count);
      group[j < 3 ? 0 : 1] |= bits << groupMaskBit(n, j);
      const uint32_t next = nextAlongW[k];
      if (next != 0xFFFFFFFFu) {
        const uint64_t nr = next * rowsPerBrick + row;
        if ((bitsOf(nr) & 1u) != 0u) {
          group[j < 3 ? 0 : 1] |= 1u << groupApronBit(n, j);
          out.voxelWords.push_back(voxelWords[firstVoxels[next] + rowStarts[nr]]);
        }
      }
    }
  return out;
}

ApronRow apronRowOf(uint32_t n, std::span<const uint32_t> rowGroups, uint64_t r) {
  const uint32_t* group = &rowGroups[r / kRowsPerGroup * 2];
  const uint32_t j = uint32_t(r % kRowsPerGroup);
  const uint32_t rowMask = (1u << n) - 1u;
  const uint32_t before = (((1u << (j * n)) - 1u) | ((1u << j) - 1u) << (3 * n)) & group[0];
  const uint32_t bits =
      j < 3 ? ((group[0] >> (j * n)) & rowMask) | ((group[0] >> groupApronBit(n, j)) & 1u) << n
            : group[1] & (2 * rowMask + 1);
  return {bits, (group[1] >> (n + 1)) + uint32_t(std::popcount(before))};
}

}  // namespace voxlink::render::gl
