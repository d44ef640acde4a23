// SPDX-License-Identifier: BSD-3-Clause
// Brick lookup tables derived from a file's occupancy bits when it is loaded (not stored in the
// file). On llvmpipe every storage-buffer read a shader executes costs a scalar loop over the
// SIMD lanes, whether or not a lane needs it, so the ray tracers read these instead of the
// occupancy and rank sections: one read gives a brick's occupied index (two before), one word
// the part of a dual brick where samples can meet voxels (eight reads gave only whether it
// had any).
// The tables cover only the box of the occupied bricks, not the whole grid: a lookup outside it
// is empty without a read, and their memory follows where the file stores voxels (one voxel in
// a 65536 x 32768 x 1 grid of 4-voxel bricks took 14 GB when the tables covered the grid).
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "base/check.h"
#include "format/voxlink_file.h"

namespace voxlink::render {

// A box of bricks (or dual cells): [lo, lo + size) per axis; size 0 on every axis when empty.
struct BrickRange {
  std::array<uint32_t, 3> lo{0, 0, 0};
  std::array<uint32_t, 3> size{0, 0, 0};
  uint64_t count() const { return uint64_t{size[0]} * size[1] * size[2]; }
  // Entry of cell (x, y, z), which must lie in the box (checked in debug builds: per cell), in
  // a table over the box (x fastest).
  uint64_t local(uint64_t x, uint64_t y, uint64_t z) const {
    VOXLINK_DCHECK(x - lo[0] < size[0] && y - lo[1] < size[1] && z - lo[2] < size[2]);
    return ((z - lo[2]) * size[1] + (y - lo[1])) * size[0] + (x - lo[0]);
  }
};

// The smallest box holding every occupied brick; empty for a file without voxels.
BrickRange occupiedBrickRange(const format::VoxLinkFile& file);

// The grid cell (x, y, z) of every occupied brick, in occupied-index order: 3 words per brick.
std::vector<uint32_t> occupiedBrickCells(const format::VoxLinkFile& file);

// Marks an empty brick in occupiedIndexByBrick().
inline constexpr uint32_t kEmptyBrick = 0xFFFFFFFFu;

// Per brick of `range` (x fastest): its index among the occupied bricks, or kEmptyBrick.
// `range` must hold every occupied brick (occupiedBrickRange()).
std::vector<uint32_t> occupiedIndexByBrick(const format::VoxLinkFile& file,
                                           const BrickRange& range);

// Dual brick D (D from -1 to grid - 1 per axis) reads the voxels of bricks D and D + 1 per axis
// (shaders/voxlink_trilinear.glsl). The dual grid is the brick grid plus one per axis; dual
// brick D sits at cell D + 1 of it.
std::array<uint32_t, 3> dualBrickGrid(const format::FileHeader& header);

// The dual cells whose dual bricks read a brick of `occupied`: brick b is read by dual cells b
// and b + 1 per axis, so the box grows by one per axis (an empty box stays empty).
BrickRange dualBrickRange(const BrickRange& occupied);

// Marks a dual brick none of whose samples can meet a stored voxel in dualBrickBoxes().
inline constexpr uint32_t kEmptyDualBrick = 0xFFFFFFFFu;

// Per dual cell of dualBrickRange(occupied) (x fastest): the cells c (q = p - 1/2 in
// [c, c + 1)) of its dual brick whose samples can blend a stored voxel, as a box packed like a
// brick box (brick_bounds.h, local to the dual brick's first cell D n), or kEmptyDualBrick. A
// sample blends the voxels floor(q) + {0, 1} per axis, so a brick whose voxels fill [lo, hi]
// reaches cells [lo - 1, hi]. Every dual cell outside the range is empty. Takes the file's
// brickBounds() (brick_bounds.h), which the caller has at hand.
std::vector<uint32_t> dualBrickBoxes(const format::VoxLinkFile& file, const BrickRange& occupied,
                                     std::span<const uint32_t> brickBoxes);

// Whether dualBrickIndices() can hold the file's occupied indices (16 bits each, one value
// marking an empty brick).
inline bool dualBrickIndicesFit(uint64_t occupiedBricks) { return occupiedBricks < 0xFFFFu; }

// Marks an empty brick in dualBrickIndices().
inline constexpr uint32_t kEmptyBrick16 = 0xFFFFu;

// Per dual cell of dualBrickRange(occupied) (x fastest), four words: the occupied indices of
// the 8 bricks its dual brick D reads, 16 bits each, brick D + (m & 1, m >> 1 & 1, m >> 2) in x,
// y, z at bits 16 m (kEmptyBrick16 for an empty brick). Entering a dual brick then reads one
// texel instead of 8 lookups (shaders/voxlink_trilinear.glsl). `brickIndex` is
// occupiedIndexByBrick(file, occupied); needs dualBrickIndicesFit().
std::vector<uint32_t> dualBrickIndices(const BrickRange& occupied,
                                       std::span<const uint32_t> brickIndex);

}  // namespace voxlink::render
