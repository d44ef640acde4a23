// SPDX-License-Identifier: BSD-3-Clause
// Per occupied brick, the box its stored voxels fill, derived from the row masks when a file is
// loaded (not stored in the file). A ray clips each occupied brick to this box before walking its
// rows, so it skips the empty part of a brick, and a brick whose voxels it misses altogether.
#pragma once

#include <cstdint>
#include <vector>

#include "format/voxlink_file.h"

namespace voxlink::render {

// Packed brick-local cells, 5 bits each (brick size <= 32): the lowest x, y, z in bits 0-14, the
// highest x, y, z in bits 15-29, both inclusive.
struct BrickBox {
  uint32_t lo[3], hi[3];
};
uint32_t packBrickBox(const BrickBox& box);
BrickBox unpackBrickBox(uint32_t word);

// One word per occupied brick, in occupied-brick order. An occupied brick holds at least one
// voxel, so its box is never empty.
std::vector<uint32_t> brickBounds(const format::VoxLinkFile& file);

}  // namespace voxlink::render
