// SPDX-License-Identifier: BSD-3-Clause
// ROWS and BVOX follow from MASK: a row's first voxel is the number of voxels in the brick's
// rows before it, a brick's first voxel the number in the bricks before it. Packed files store
// neither when they match (codec kDerived, pack/detail/section_codec.h); unpacking computes them
// here, and the original checksums then confirm them.
#pragma once

#include <cstdint>
#include <span>
#include <string>

#include "base/error.h"

namespace voxlink::format {

// `masks`: the MASK words of K occupied bricks of edge n. `rowStarts`: u16[K*n*n] bytes;
// `brickBase`: u32[K+1] bytes. A size that does not fit K bricks is an error naming `where`.
// Row starts are computed on `threads` threads (0: every core).
Status deriveRowStarts(std::span<const uint8_t> masks, uint32_t n, std::span<uint8_t> rowStarts,
                       const std::string& where, unsigned threads = 0);

// Whether `rowStarts` holds what deriveRowStarts would write, compared a range of bricks at a
// time (no copy of the whole section).
bool rowStartsMatch(std::span<const uint8_t> masks, uint32_t n, std::span<const uint8_t> rowStarts,
                    unsigned threads = 0);
Status deriveBrickVoxelBase(std::span<const uint8_t> masks, uint32_t n,
                            std::span<uint8_t> brickBase, const std::string& where);

}  // namespace voxlink::format
