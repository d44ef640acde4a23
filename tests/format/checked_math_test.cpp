// SPDX-License-Identifier: BSD-3-Clause
// The overflow-checked size arithmetic every reader and writer uses for sizes from files.
#include "base/checked_math.h"

#include <gtest/gtest.h>

namespace voxlink {
namespace {

TEST(CheckedMath, DetectsOverflowAtTheBoundary) {
  const uint64_t max = ~uint64_t{0};
  EXPECT_EQ(checkedAdd(max - 1, 1), max);
  EXPECT_FALSE(checkedAdd(max, 1));
  EXPECT_EQ(checkedMul(uint64_t{1} << 32, (uint64_t{1} << 32) - 1),
            max - ((uint64_t{1} << 32) - 1));
  EXPECT_FALSE(checkedMul(uint64_t{1} << 32, uint64_t{1} << 32));
  EXPECT_EQ(checkedMul(0, max), 0u);
  // 2^22 * 2^21 * 2^21 * 8 is 2^67: wraps to 0 unchecked.
  EXPECT_FALSE(checkedProduct({4194304, 2097152, 2097152, 8}));
  EXPECT_EQ(checkedProduct({65536, 65536, 256, 8}), uint64_t{1} << 43);
  EXPECT_EQ(checkedProduct({}), 1u);
}

}  // namespace
}  // namespace voxlink
