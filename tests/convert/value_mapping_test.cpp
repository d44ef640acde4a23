#include "convert/value_mapping.h"

#include <gtest/gtest.h>

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

}  // namespace
}  // namespace voxlink::convert
