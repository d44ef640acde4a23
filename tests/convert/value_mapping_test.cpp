// SPDX-License-Identifier: BSD-3-Clause
#include "convert/detail/value_mapping.h"

#include <gtest/gtest.h>

#include <array>
#include <limits>
#include <vector>

#include "format/source_value.h"

namespace voxlink::convert {
namespace {

TEST(ValueMapping, SmallestLosslessTypeForTheKeptRange) {
  auto m = chooseValueMapping(ScalarType::kU8, 60, 255, std::nullopt, 0);
  ASSERT_TRUE(m);
  EXPECT_EQ(m->type, StoredType::kU8);
  EXPECT_EQ(m->offset, 0.0);  // u8 values stay as they are
  m = chooseValueMapping(ScalarType::kI16, 0, 3926, std::nullopt, 0);
  EXPECT_EQ(m->type, StoredType::kU16);
  EXPECT_EQ(m->errorBound, 0.0);
  m = chooseValueMapping(ScalarType::kI16, -1000, -800, std::nullopt, 0);
  EXPECT_EQ(m->type, StoredType::kU8);
  EXPECT_EQ(m->offset, -1000.0);
  EXPECT_EQ(m->decode(m->encode(-873)), -873.0);
  m = chooseValueMapping(ScalarType::kF32, -3, 3, std::nullopt, 0);
  EXPECT_EQ(m->type, StoredType::kF32);
  EXPECT_EQ(m->errorBound, 0.0);
  m = chooseValueMapping(ScalarType::kF64, -3, 3, std::nullopt, 0);
  EXPECT_EQ(m->type, StoredType::kF32);
  EXPECT_GT(m->errorBound, 0.0);
}

TEST(ValueMapping, ErrorBoundPicksTheSmallestTypeWithinIt) {
  // N(0,1) values kept outside +-1.96, up to +-5.
  auto m = chooseValueMapping(ScalarType::kF64, -5, 5, std::nullopt, 0.05);
  ASSERT_TRUE(m);
  EXPECT_EQ(m->type, StoredType::kU8);
  EXPECT_LE(m->errorBound, 0.05);
  m = chooseValueMapping(ScalarType::kF64, -5, 5, std::nullopt, 1e-3);
  EXPECT_EQ(m->type, StoredType::kU16);
  m = chooseValueMapping(ScalarType::kF64, -5, 5, std::nullopt, 1e-6);
  EXPECT_EQ(m->type, StoredType::kF32);
  // Every quantized value really is within the bound.
  m = chooseValueMapping(ScalarType::kF64, -5, 5, std::nullopt, 1e-3);
  for (double v = -5; v <= 5; v += 0.0137)
    EXPECT_LE(std::abs(m->decode(m->encode(v)) - v), m->errorBound + 1e-15);
  EXPECT_FALSE(chooseValueMapping(ScalarType::kF64, -1e30, 1e30, std::nullopt, 1e-9));
}

TEST(ValueMapping, RequestedType) {
  auto m = chooseValueMapping(ScalarType::kF32, -1, 1, StoredType::kF16, 0);
  ASSERT_TRUE(m);
  EXPECT_EQ(m->type, StoredType::kF16);
  EXPECT_FALSE(
      chooseValueMapping(ScalarType::kF32, 0, 1e6, StoredType::kF16, 0));  // beyond half range
  EXPECT_FALSE(
      chooseValueMapping(ScalarType::kF64, 0, 100, StoredType::kU8, 0.01));  // bound not met
}

}  // namespace
}  // namespace voxlink::convert

namespace voxlink::convert {
namespace {

TEST(ValueMapping, F64BeyondFloatRangeIsScaledNotInfinite) {
  for (double hi : {1e300, 3.4e38, 0x1p127, 1.7e308}) {
    SCOPED_TRACE(hi);
    auto m = chooseValueMapping(ScalarType::kF64, -hi, hi, std::nullopt, 0);
    ASSERT_TRUE(m) << m.message();
    EXPECT_EQ(m->type, StoredType::kF32);
    for (double v : {hi, -hi, hi / 3, 1.0, 0.0}) {
      const double back = m->decode(m->encode(v));
      EXPECT_TRUE(std::isfinite(back)) << v;
      EXPECT_LE(std::abs(back - v), m->errorBound) << v;
    }
  }
  // Within f32 rounding of the largest double nothing can hold it: a one-line error.
  auto top = chooseValueMapping(ScalarType::kF64, 0, 1.7976931348623157e308, std::nullopt, 0);
  ASSERT_FALSE(top);
  EXPECT_NE(top.message().find("cannot be stored"), std::string::npos) << top.message();
  // Within float's range nothing changes.
  auto m = chooseValueMapping(ScalarType::kF64, -1e30, 1e30, std::nullopt, 0);
  ASSERT_TRUE(m);
  EXPECT_EQ(m->scale, 1.0);
}

TEST(ValueMapping, F32SourceIsStoredUnscaledKeepingItsSubnormals) {
  // 3e38 is above 2^127; a scale of 4 (as f64 sources get) would flush 1.4e-45 to 0.
  const double tiny = double(std::numeric_limits<float>::denorm_min());
  auto m = chooseValueMapping(ScalarType::kF32, tiny, 3e38, std::nullopt, 0, tiny);
  ASSERT_TRUE(m) << m.message();
  EXPECT_EQ(m->type, StoredType::kF32);
  EXPECT_EQ(m->scale, 1.0);
  EXPECT_EQ(m->errorBound, 0.0);
  for (float v : {3e38f, -3e38f, std::numeric_limits<float>::denorm_min(), 1.0f})
    EXPECT_EQ(m->decode(m->encode(v)), double(v)) << v;
}

TEST(ValueMapping, F64MagnitudesOneScaleCannotHoldAreRefusedWithTheNumbers) {
  // [1e300, 1, 0.5, -12345.678]: one scale for 1e300 sends 1 below float's range.
  auto m = chooseValueMapping(ScalarType::kF64, -12345.678, 1e300, std::nullopt, 0, 0.5);
  ASSERT_FALSE(m);
  EXPECT_EQ(m.code(), ErrorCode::kUnsupported);
  for (const char* part : {"0.5", "1e+300", "--error-bound", "--threshold"})
    EXPECT_NE(m.message().find(part), std::string::npos) << part << ": " << m.message();
  // The same with f32 asked for by name; an absolute bound accepts the loss of the small ones.
  EXPECT_FALSE(chooseValueMapping(ScalarType::kF64, -1, 1e300, StoredType::kF32, 0, 0.5));
  m = chooseValueMapping(ScalarType::kF64, -12345.678, 1e300, std::nullopt, 1e293, 0.5);
  ASSERT_TRUE(m) << m.message();
  EXPECT_FALSE(m->keepsRelativeError);
  EXPECT_LE(std::abs(m->decode(m->encode(1.0)) - 1.0), 1e293);
}

TEST(ValueMapping, F64ScaleKeepsRelativeErrorAtBothEnds) {
  // Beyond float's range, below it (1e-300 is far under float's smallest), and spanning 2^252.
  const std::vector<std::array<double, 2>> ranges = {{1e250, 1e300},
                                                     {1e-300, 2e-300},
                                                     {0x1p-126, 0x1.fp126},
                                                     {0x1p-125, 0x1p127},
                                                     {1e-310, 1e-300}};
  for (const auto& [lo, hi] : ranges) {
    SCOPED_TRACE(lo);
    auto m = chooseValueMapping(ScalarType::kF64, lo, hi, std::nullopt, 0, lo);
    ASSERT_TRUE(m) << m.message();
    EXPECT_TRUE(m->keepsRelativeError);
    for (double v : {lo, hi, -lo, std::sqrt(lo) * std::sqrt(hi), lo * 1.37}) {
      const double back = m->decode(m->encode(v));
      EXPECT_LE(std::abs(back - v), std::abs(v) * 0x1p-24) << v;
    }
  }
  // Exponents 253 apart are one too many.
  EXPECT_FALSE(chooseValueMapping(ScalarType::kF64, 0x1p-127, 0x1p126, std::nullopt, 0, 0x1p-127));
}

TEST(ValueMapping, QuantizedIntegerBoundIncludesRoundingToWholeNumbers) {
  // i16 values 0..300 in u8: levels 1.18 apart; given back as whole numbers, an error of 0.59
  // becomes 1. The bound says so, and holds for every value.
  auto m = chooseValueMapping(ScalarType::kI16, 0, 300, StoredType::kU8, 0);
  ASSERT_TRUE(m);
  EXPECT_EQ(m->errorBound, 1.0);
  double worst = 0;
  for (int v = 0; v <= 300; ++v)
    worst = std::max(worst, std::abs(asSourceValueOf<int16_t>(m->decode(m->encode(v))) - v));
  EXPECT_EQ(worst, 1.0);
  // So a bound of 0.6, which u8's levels alone would meet, takes u16 (lossless) instead.
  m = chooseValueMapping(ScalarType::kI16, 0, 300, std::nullopt, 0.6);
  ASSERT_TRUE(m);
  EXPECT_EQ(m->type, StoredType::kU16);
  EXPECT_EQ(m->errorBound, 0.0);
}

TEST(ValueMapping, Int32NearItsMaximumComesBackClamped) {
  // f32 rounds 2147483647 and 2147483600 up to 2^31: given back as i32 they are clamped, not
  // wrapped to -2^31; u32 4294967295 rounds to 2^32 and comes back as 4294967295, not 0.
  auto m = chooseValueMapping(ScalarType::kI32, -2147483648.0, 2147483647.0, std::nullopt, 0);
  ASSERT_TRUE(m);
  ASSERT_EQ(m->type, StoredType::kF32);
  EXPECT_EQ(asSourceValueOf<int32_t>(m->decode(m->encode(2147483647))), 2147483647.0);
  EXPECT_EQ(asSourceValueOf<int32_t>(m->decode(m->encode(2147483600))), 2147483647.0);
  EXPECT_EQ(asSourceValueOf<int32_t>(m->decode(m->encode(-2147483648.0))), -2147483648.0);
  m = chooseValueMapping(ScalarType::kU32, 0, 4294967295.0, std::nullopt, 0);
  ASSERT_TRUE(m);
  EXPECT_EQ(asSourceValueOf<uint32_t>(m->decode(m->encode(4294967295.0))), 4294967295.0);
}

}  // namespace
}  // namespace voxlink::convert
