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

// The words of `bricks` occupied bricks of size n (rowWordsFit(n)) from MASK (n^3 / 32 words per
// brick, n bits per row) and ROWS (n^2 starts per brick).
std::vector<uint32_t> packRowWords(uint32_t n, uint64_t bricks, std::span<const uint32_t> maskWords,
                                   std::span<const uint16_t> rowStarts);

}  // namespace voxlink::render::gl
