// SPDX-License-Identifier: BSD-3-Clause
// One 32-bit word per stored voxel, built at load time, that the shaders read in place of the
// file's 16-bit polar gradient codes (format/gradient_codec.h) and, for 8-bit values, of VALU:
// the decoded gradient direction in octahedral coordinates, two 12-bit signed integers
// (value * 2047, rounded) in bits 0-11 and 12-23, and the 8-bit value in bits 24-31 (0 for
// wider values, which stay in VALU). A trilinear cell then costs one texel fetch per corner
// for value and direction where it cost two (docs/rendering-benchmark.md); decoding a code on
// the GPU took two table reads. The rounding moves a direction by at most 0.06 degrees (0.1 for
// the three 10-bit components it replaced); the GPU renormalizes. The zero gradient is
// x = -2048 (kZeroDirectionWord).
#pragma once

#include <cstdint>
#include <span>
#include <vector>

namespace voxlink::render::gl {

inline constexpr uint32_t kZeroDirectionWord = 0x800u;

// Bits 0-23 of a voxel word: the direction of gradient code `code`.
uint32_t packGradientDirection(uint16_t code);

// The words of a file's voxels: GRAD's little-endian 16-bit codes, and `values8` the VALU
// section of an 8-bit file (one byte per voxel) or empty.
std::vector<uint32_t> packVoxelWords(std::span<const uint8_t> codes,
                                     std::span<const uint8_t> values8);

}  // namespace voxlink::render::gl
