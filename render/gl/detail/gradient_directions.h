// SPDX-License-Identifier: BSD-3-Clause
// Gradient directions decoded once at load time, one 32-bit word per stored voxel in place of
// the file's 16-bit polar codes (format/gradient_codec.h): x, y, z as 10-bit signed integers
// (value * 511, rounded) in bits 0-9, 10-19 and 20-29. Decoding a code on the GPU took two table
// reads per voxel, a sixth of a trilinear frame on llvmpipe (docs/rendering-benchmark.md);
// unpacking a word is a few bit operations. The rounding moves a direction by at most 0.1
// degrees; the GPU renormalizes. Zero-gradient codes give the zero word.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

namespace voxlink::render::gl {

uint32_t packGradientDirection(uint16_t code);

// One word per code of a GRAD section (little-endian 16-bit codes).
std::vector<uint32_t> packGradientDirections(std::span<const uint8_t> codes);

}  // namespace voxlink::render::gl
