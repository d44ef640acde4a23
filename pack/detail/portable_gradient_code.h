// SPDX-License-Identifier: BSD-3-Clause
// A gradient encoder in float whose codes are the same bits on every machine and compiler: only
// IEEE basic operations (+ - * / sqrt and comparisons, no fused multiply-add, no libm), so a
// vectorized loop and a scalar one agree. Packed files predict their gradients with it
// (pack/detail/gradient_predictor.h, codec "predicted-f32"); the converter's own encoder
// (encodeGradients) is faster per call but picks its arithmetic by CPU, so it cannot serve as
// part of a file format.
//
// It follows encodeGradientReference (round theta and phi to the nearest step) with float
// arctangents of about 1e-7 rad error: it agrees with the float64 reference except for
// directions within about that of a cell's border (tests/format/portable_gradient_code_test.cpp).
#pragma once

#include <cstdint>

namespace voxlink::pack {

// codes[j] = the code of (x[j], y[j], z[j]); zero or non-finite input gives kZeroGradient.
void portableGradientCodes(const float* x, const float* y, const float* z, uint16_t* codes,
                           uint32_t count);

}  // namespace voxlink::pack
