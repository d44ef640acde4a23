// SPDX-License-Identifier: BSD-3-Clause
#include "format/half.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>
#include <vector>

namespace voxlink::format {
namespace {

// The hand-written conversions format/half.cpp had before it used Imath, kept as the reference
// the library's results must match bit for bit (.vxl files written before stay identical).
float referenceHalfToFloat(uint16_t h) {
  const uint32_t sign = uint32_t(h & 0x8000) << 16;
  uint32_t exponent = (h >> 10) & 0x1F;
  uint32_t mantissa = h & 0x3FF;
  uint32_t bits;
  if (exponent == 0x1F) {
    bits = sign | 0x7F800000u | (mantissa << 13);
  } else if (exponent != 0) {
    bits = sign | ((exponent + 112) << 23) | (mantissa << 13);
  } else if (mantissa == 0) {
    bits = sign;
  } else {
    exponent = 113;
    while ((mantissa & 0x400) == 0) {
      mantissa <<= 1;
      --exponent;
    }
    bits = sign | (exponent << 23) | ((mantissa & 0x3FF) << 13);
  }
  float f;
  std::memcpy(&f, &bits, 4);
  return f;
}

uint16_t referenceFloatToHalf(float f) {
  uint32_t bits;
  std::memcpy(&bits, &f, 4);
  const uint16_t sign = static_cast<uint16_t>((bits >> 16) & 0x8000);
  const uint32_t absBits = bits & 0x7FFFFFFFu;
  if (absBits >= 0x7F800000u) return sign | 0x7C00 | (absBits > 0x7F800000u ? 0x200 : 0);
  if (absBits >= 0x477FF000u) return sign | 0x7C00;
  if (absBits < 0x38800000u) {
    if (absBits < 0x33000000u) return sign;
    const uint32_t exponent = absBits >> 23;
    const uint32_t mantissa = (absBits & 0x7FFFFF) | 0x800000;
    const uint32_t shift = 126 - exponent;
    uint32_t half = mantissa >> shift;
    const uint32_t rest = mantissa & ((1u << shift) - 1);
    const uint32_t halfway = 1u << (shift - 1);
    if (rest > halfway || (rest == halfway && (half & 1))) ++half;
    return sign | static_cast<uint16_t>(half);
  }
  uint32_t half = ((absBits >> 13) - (112u << 10));
  const uint32_t rest = absBits & 0x1FFF;
  if (rest > 0x1000 || (rest == 0x1000 && (half & 1))) ++half;
  return sign | static_cast<uint16_t>(half);
}

uint32_t bitsOf(float f) {
  uint32_t b;
  std::memcpy(&b, &f, 4);
  return b;
}

float floatOf(uint32_t b) {
  float f;
  std::memcpy(&f, &b, 4);
  return f;
}

// Float bit patterns where rounding decides: below, at and above every tie of the normal
// range, the same for each subnormal exponent's tie bit, NaNs with payloads, infinities,
// the overflow edge, and random patterns.
std::vector<uint32_t> floatSweep() {
  std::vector<uint32_t> out;
  for (uint32_t high = 0; high < (1u << 19); ++high)
    for (uint32_t low : {0x0u, 0x1u, 0xFFFu, 0x1000u, 0x1001u, 0x1FFFu})
      out.push_back((high << 13) | low);
  for (uint32_t exponent = 100; exponent < 114; ++exponent) {
    const uint32_t shift = exponent <= 126 ? 126 - exponent : 0;  // 13..26
    const uint32_t tie = 1u << (shift - 1);
    for (uint32_t upper = 0; upper < (1u << 10); ++upper)
      for (uint32_t low : {0u, 1u, tie - 1, tie, tie + 1, 2 * tie - 1}) {
        const uint32_t fraction = ((upper << shift) | low) & 0x7FFFFF;
        out.push_back((exponent << 23) | fraction);
        out.push_back(0x80000000u | (exponent << 23) | fraction);
      }
  }
  for (uint32_t b :
       {0x7F800000u, 0x7F800001u, 0x7FC00000u, 0x7FBFFFFFu, 0x7FFFFFFFu, 0x7F802000u, 0x477FEFFFu,
        0x477FF000u, 0x477FE000u, 0x7F7FFFFFu, 0x33000000u, 0x33000001u, 0x387FFFFFu, 0x38800000u})
    for (uint32_t sign : {0u, 0x80000000u}) out.push_back(sign | b);
  std::mt19937 random(31);
  for (int i = 0; i < 4'000'000; ++i) out.push_back(static_cast<uint32_t>(random()));
  return out;
}

TEST(Half, EveryHalfConvertsToTheSameFloatBitsAsTheReference) {
  for (uint32_t h = 0; h < 0x10000; ++h)
    ASSERT_EQ(bitsOf(halfToFloat(static_cast<uint16_t>(h))),
              bitsOf(referenceHalfToFloat(static_cast<uint16_t>(h))))
        << std::hex << h;
}

TEST(Half, FloatSweepConvertsToTheSameHalfBitsAsTheReference) {
  size_t nans = 0, subnormals = 0;
  for (uint32_t b : floatSweep()) {
    const float f = floatOf(b);
    nans += std::isnan(f);
    subnormals += (referenceFloatToHalf(f) & 0x7C00) == 0 && (referenceFloatToHalf(f) & 0x3FF);
    ASSERT_EQ(floatToHalf(f), referenceFloatToHalf(f)) << std::hex << b;
  }
  EXPECT_GT(nans, 100u);  // the sweep reaches the cases it is for
  EXPECT_GT(subnormals, 10000u);
}

TEST(Half, EveryHalfRoundTripsThroughFloat) {
  for (uint32_t h = 0; h < 0x10000; ++h) {
    const float f = halfToFloat(static_cast<uint16_t>(h));
    if (std::isnan(f)) {
      EXPECT_EQ(floatToHalf(f), (h & 0x8000) | 0x7E00) << std::hex << h;  // one quiet NaN
      continue;
    }
    EXPECT_EQ(floatToHalf(f), h) << std::hex << h;
  }
}

TEST(Half, RoundsToNearestEven) {
  EXPECT_EQ(halfToFloat(floatToHalf(1.0f + 1.0f / 2048)), 1.0f);  // tie -> even
  EXPECT_EQ(halfToFloat(floatToHalf(1.0f + 3.0f / 2048)), 1.0f + 4.0f / 2048);
  EXPECT_TRUE(std::isinf(halfToFloat(floatToHalf(70000.0f))));
  EXPECT_EQ(halfToFloat(floatToHalf(65504.0f)), 65504.0f);
  EXPECT_EQ(halfToFloat(floatToHalf(1e-9f)), 0.0f);
  EXPECT_EQ(halfToFloat(floatToHalf(5.960464477539063e-08f)), 5.960464477539063e-08f);
}

}  // namespace
}  // namespace voxlink::format
