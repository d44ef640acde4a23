// SPDX-License-Identifier: BSD-3-Clause
// One 32-bit word per stored voxel, built at load time, that the shaders read in place of the
// file's 16-bit polar gradient codes (format/gradient_codec.h) and, for 8-bit values, of VALU:
// the decoded unit gradient direction as three 8-bit signed integers (value * 127, rounded) in
// bits 0-7, 8-15 and 16-23, and the 8-bit value in bits 24-31 (0 for wider values, which stay
// in VALU). A trilinear cell then costs one texel fetch per corner for value and direction where
// it cost two, and unpacking needs no normalization: the rounding moves a direction by at most
// 0.4 degrees and its length by under 1 %, which the shading's blend of 8 corners tolerates
// (PSNR in docs/rendering-benchmark.md). Octahedral 12-bit pairs (0.06 degrees) needed an
// unfold and a normalization per corner, 5 % more of a trilinear frame's instructions.
// The zero gradient is the zero word.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

namespace voxlink::render::gl {

// Bits 0-23 of a voxel word: the direction of gradient code `code`.
uint32_t packGradientDirection(uint16_t code);

// The words of a file's voxels: GRAD's little-endian 16-bit codes, and `values8` the VALU
// section of an 8-bit file (one byte per voxel) or empty.
std::vector<uint32_t> packVoxelWords(std::span<const uint8_t> codes,
                                     std::span<const uint8_t> values8);

}  // namespace voxlink::render::gl
