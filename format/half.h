// SPDX-License-Identifier: BSD-3-Clause
// IEEE 754 binary16 conversion (round to nearest even), for the f16 stored value type; NaNs
// written as one quiet NaN (0x7E00, sign kept).
#pragma once

#include <cstdint>

namespace voxlink::format {

float halfToFloat(uint16_t h);
uint16_t floatToHalf(float f);

}  // namespace voxlink::format
