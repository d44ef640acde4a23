// SPDX-License-Identifier: BSD-3-Clause
// A brick's stored voxels as a dense block with a one-cell halo, and the central differences of
// its stored voxels, eight cells of a row at a time (AVX2 on x86-64). The gradient prediction of
// packed files uses them for bricks away from the volume's faces; they move and subtract floats
// exactly as the per-voxel code does, so the predicted codes keep their bits.
//
// The block is (n + 2)^3 floats in brick-row order: cell (w, u, v) of the padded brick, each
// coordinate in [0, n + 1], is at w + p * (u + p * v) with p = n + 2, so a brick row (depth axis
// w) is contiguous and the brick's voxels lie in the block in file order.
#pragma once

#include <cstdint>

namespace voxlink::pack {

// Whether this CPU runs the kernels below (brick sizes of 8 or more; smaller ones are not
// supported).
bool denseBrickRowsAvailable();

// Writes the n^3 interior cells of `block`: the k-th set bit of the brick's mask (in row order)
// takes values[k], every other cell `fill`. Returns the number of set bits. `values` must have
// at least that many entries plus 8 readable floats after them.
uint32_t expandBrickRows(const uint32_t* brickMask, uint32_t n, const float* values, float fill,
                         float* block);

// Writes `rows` rows of n cells, row i from cells + i * step: cell d of row i takes the next of
// `values` where bit d of bits[i] is set, `fill` elsewhere (the faces of neighbouring bricks in
// the halo). `values` needs 8 readable floats after the last one taken.
void expandRows(const uint32_t* bits, uint32_t rows, uint32_t n, const float* values, float fill,
                float* cells, uint32_t step);

// For every set bit of the mask, in row order: g_w = (block[c + 1] - block[c - 1]) * half[0],
// g_u with the step p and half[1], g_v with p^2 and half[2]. Returns their count; each output
// array needs room for it plus 8 floats.
uint32_t brickCentralDifferences(const uint32_t* brickMask, uint32_t n, const float* block,
                                 const float half[3], float* gw, float* gu, float* gv);

}  // namespace voxlink::pack
