// SPDX-License-Identifier: BSD-3-Clause
// One 32-bit word per row of every occupied brick, built at load time, that the shaders read in
// place of the file's MASK and ROWS sections when bricks are at most 16^3: the row's n mask bits
// in bits 0 to n-1 and the index of its first voxel among its brick's voxels (below n^3, at most
// 12 bits) above them. A row then costs one texel fetch where mask and start took two; a
// trilinear cell reads 8 rows (docs/rendering-benchmark.md). 32^3 bricks keep both sections.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

namespace voxlink::render::gl {

inline constexpr bool rowWordsFit(uint32_t brickSize) { return brickSize <= 16; }

// Whether the start above the mask bits can be the row's first voxel in the whole file (its
// brick's first voxel added): bricks up to 8^3 leave 24 bits, files below 16.7M voxels. The
// trilinear caster then reads no brick's first voxel (8 fetches per dual brick) and selects none
// per corner (docs/rendering-trilinear-profile.md, fourth session). Shaders see VXL_ROW_GLOBAL.
inline constexpr bool rowWordsGlobal(uint32_t brickSize, uint64_t voxelCount) {
  return brickSize <= 8 && voxelCount < (uint64_t(1) << (32 - brickSize));
}

// The words of `bricks` occupied bricks of size n (rowWordsFit(n)) from MASK (n^3 / 32 words per
// brick, n bits per row) and ROWS (n^2 starts per brick); with firstVoxels (BVOX, one per brick,
// rowWordsGlobal) the starts are the file's voxel indices, without it the brick's.
std::vector<uint32_t> packRowWords(uint32_t n, uint64_t bricks, std::span<const uint32_t> maskWords,
                                   std::span<const uint16_t> rowStarts,
                                   std::span<const uint32_t> firstVoxels = {});

// Row words with an apron (VXL_ROW_APRON), for bricks up to 8^3 of 8-bit files that are not
// scenes: bit n says that the brick next along w holds a voxel at depth 0 of the same row, whose
// word then follows the row's own voxels as a copy, and the start (above bit n) indexes these
// extended voxel words. A trilinear cell's pairs of corners along w then sit in one row word
// even where the pair crosses a brick face: 4 row fetches per cell instead of 8
// (docs/rendering-trilinear-profile.md, fifth session). The copies cost 4 bytes each, at most
// one per row. Other readers see the row's n mask bits and the same voxels as without it.
inline bool rowWordsApronFit(uint32_t brickSize, uint64_t voxelCount, uint64_t rows) {
  return brickSize <= 8 && voxelCount + rows < (uint64_t(1) << (31 - brickSize));
}

struct ApronRows {
  std::vector<uint32_t> rowWords;
  std::vector<uint32_t> voxelWords;
};

// The row words and extended voxel words of `bricks` occupied bricks of size n from MASK, ROWS,
// BVOX (firstVoxels), the voxel words in file order, and per occupied brick the occupied index
// of the brick next to it along w (kEmptyBrick, brick_lookup.h, where there is none).
ApronRows packApronRows(uint32_t n, uint64_t bricks, std::span<const uint32_t> maskWords,
                        std::span<const uint16_t> rowStarts, std::span<const uint32_t> firstVoxels,
                        std::span<const uint32_t> voxelWords, std::span<const uint32_t> nextAlongW);

// Row groups: the same apron rows, four of a brick that follow one another in its row order in
// one group of two words (8 bytes where the row words took 16). Word 0 holds the mask bits of rows
// 0, 1 and 2 at bits 0, n and 2 n and their apron bits at bits 3 n to 3 n + 2; word 1 is row 3's
// row word, but with the start of row 0. The start of row j is row 0's plus the set bits of word
// 0 that belong to rows 0..j-1 (one bitCount in the shaders), as the extended voxel words hold
// each row's voxels and copy one after another. The foot CT 256^3 takes 4.71 MiB of GPU memory
// with them, 5.5 MiB with row words (docs/gpu-measurements.md), but on llvmpipe their 8-byte
// fetch and the bitCount cost 2-14 % of a frame (docs/rendering-trilinear-profile.md, eighth
// session): SectionBuffers uses them on GPUs only (section_buffers.h).
inline constexpr uint32_t kRowsPerGroup = 4;

// The groups (two words each) of apron row words `rowWords` of bricks of size n.
std::vector<uint32_t> packRowGroups(uint32_t n, std::span<const uint32_t> rowWords);

// Row word r as the shaders read it from the groups (VXL_ROW_GROUPS): the inverse of
// packRowGroups.
uint32_t rowWordOfGroups(uint32_t n, std::span<const uint32_t> rowGroups, uint64_t r);

}  // namespace voxlink::render::gl
