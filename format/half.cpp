// SPDX-License-Identifier: BSD-3-Clause
#include "format/half.h"

#include <Imath/half.h>

#include <cstring>

namespace voxlink::format {
namespace {

constexpr uint32_t kHalfExponent = 0x7C00;
constexpr uint32_t kFloatExponent = 0x7F800000u;

}  // namespace

// Imath does the conversions; NaNs stay ours so that bits do not depend on -march: with F16C
// (x86-64-v3) Imath converts in hardware, which quiets signalling NaNs and keeps payloads.
float halfToFloat(uint16_t h) {
  if ((h & kHalfExponent) == kHalfExponent && (h & 0x3FF) != 0) {  // NaN: payload kept as is
    const uint32_t bits =
        (uint32_t(h & 0x8000) << 16) | kFloatExponent | (uint32_t(h & 0x3FF) << 13);
    float f;
    std::memcpy(&f, &bits, 4);
    return f;
  }
  return imath_half_to_float(h);
}

uint16_t floatToHalf(float f) {
  uint32_t bits;
  std::memcpy(&bits, &f, 4);
  if ((bits & 0x7FFFFFFFu) > kFloatExponent)  // NaN: one quiet NaN, whatever the payload
    return static_cast<uint16_t>(((bits >> 16) & 0x8000) | kHalfExponent | 0x200);
  return imath_float_to_half(f);
}

}  // namespace voxlink::format
