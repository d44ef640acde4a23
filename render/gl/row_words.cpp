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

std::vector<uint32_t> packRowGroups(uint32_t n, std::span<const uint32_t> rowWords) {
  const uint32_t rowMask = (1u << n) - 1u;
  std::vector<uint32_t> groups(rowWords.size() / kRowsPerGroup * 2, 0u);
  for (uint64_t g = 0; g < rowWords.size() / kRowsPerGroup; ++g) {
    const uint32_t* rows = &rowWords[g * kRowsPerGroup];
    for (uint32_t j = 0; j < 3; ++j)
      groups[2 * g] |= (rows[j] & rowMask) << (j * n) | ((rows[j] >> n) & 1u) << (3 * n + j);
    groups[2 * g + 1] = (rows[3] & (2 * rowMask + 1)) | (rows[0] >> (n + 1)) << (n + 1);
  }
  return groups;
}

uint32_t rowWordOfGroups(uint32_t n, std::span<const uint32_t> rowGroups, uint64_t r) {
  const uint32_t x = rowGroups[r / kRowsPerGroup * 2], y = rowGroups[r / kRowsPerGroup * 2 + 1];
  const uint32_t j = uint32_t(r % kRowsPerGroup), rowMask = (1u << n) - 1u;
  const uint32_t before = (((1u << (j * n)) - 1u) | ((1u << j) - 1u) << (3 * n)) & x;
  const uint32_t bits =
      j < 3 ? ((x >> (j * n)) & rowMask) | ((x >> (3 * n + j)) & 1u) << n : y & (2 * rowMask + 1);
  return bits | ((y >> (n + 1)) + uint32_t(std::popcount(before))) << (n + 1);
}

}  // namespace voxlink::render::gl
