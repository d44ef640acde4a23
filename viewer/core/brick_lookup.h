// Brick lookup tables derived from a file's occupancy bits when it is loaded (not stored in the
// file). On llvmpipe every storage-buffer read a shader executes costs a scalar loop over the
// SIMD lanes, whether or not a lane needs it, so the ray tracers read these instead of the
// occupancy and rank sections: one read gives a brick's occupied index (two before), one bit
// tells whether a dual brick reads any voxels (eight reads before).
#pragma once

#include <array>
#include <cstdint>
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

// One bit per dual brick (x fastest over dualBrickGrid(), 32 per word): set when any of the 8
// bricks it reads is occupied.
std::vector<uint32_t> dualBrickOccupancy(const format::VoxLinkFile& file);

}  // namespace voxlink::viewer
