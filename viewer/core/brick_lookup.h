// Brick lookup tables derived from a file's occupancy bits when it is loaded (not stored in the
// file). On llvmpipe every storage-buffer read a shader executes costs a scalar loop over the
// SIMD lanes, whether or not a lane needs it, so the ray tracers read these instead of the
// occupancy and rank sections: one read gives a brick's occupied index (two before), one word
// the part of a dual brick where samples can meet voxels (eight reads gave only whether it
// had any).
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "format/voxlink_file.h"

namespace voxlink::viewer {

// Marks an empty brick in occupiedIndexByBrick().
inline constexpr uint32_t kEmptyBrick = 0xFFFFFFFFu;

// Per brick of the grid (x fastest, as format/layout.h numbers them): its index among the
// occupied bricks, or kEmptyBrick.
std::vector<uint32_t> occupiedIndexByBrick(const format::VoxLinkFile& file);

// Dual brick D (D from -1 to grid - 1 per axis) reads the voxels of bricks D and D + 1 per axis
// (shaders/voxlink_trilinear.glsl). The dual grid is the brick grid plus one per axis; dual
// brick D sits at cell D + 1 of it.
std::array<uint32_t, 3> dualBrickGrid(const format::FileHeader& header);

// Marks a dual brick none of whose samples can meet a stored voxel in dualBrickBoxes().
inline constexpr uint32_t kEmptyDualBrick = 0xFFFFFFFFu;

// Per dual brick (x fastest over dualBrickGrid()): the cells c (q = p - 1/2 in [c, c + 1)) of
// it whose samples can blend a stored voxel, as a box packed like a brick box (brick_bounds.h,
// local to the dual brick's first cell D n), or kEmptyDualBrick. A sample blends the voxels
// floor(q) + {0, 1} per axis, so a brick whose voxels fill [lo, hi] reaches cells [lo - 1, hi].
// Takes the file's occupiedIndexByBrick() and brickBounds() (brick_bounds.h), which the caller
// has at hand.
std::vector<uint32_t> dualBrickBoxes(const format::FileHeader& header,
                                     std::span<const uint32_t> brickIndex,
                                     std::span<const uint32_t> brickBoxes);

}  // namespace voxlink::viewer
