// IEEE 754 binary16 conversion (round to nearest even), for the f16 stored value type.
#pragma once

#include <cstdint>

namespace voxlink::format {

float halfToFloat(uint16_t h);
uint16_t floatToHalf(float f);

}  // namespace voxlink::format
