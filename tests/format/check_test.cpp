// SPDX-License-Identifier: BSD-3-Clause
// VOXLINK_CHECK holds in release builds: misusing Status or Result stops the process with a
// message instead of reading an empty optional. The comparison checks print both operands;
// VOXLINK_DCHECK evaluates nothing in NDEBUG builds.
#include "base/check.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <string>

#include "base/error.h"

namespace voxlink {
namespace {

TEST(CheckDeathTest, FailedCheckAbortsWithTheCondition) {
  EXPECT_DEATH(VOXLINK_CHECK(1 + 1 == 3, "arithmetic"),
               "VOXLINK_CHECK\\(1 \\+ 1 == 3\\) failed: arithmetic");
}

TEST(CheckDeathTest, ACheckWithoutAMessageNamesTheCondition) {
  const int width = 3;
  EXPECT_DEATH(VOXLINK_CHECK(width > 4),
               "check_test.cpp:[0-9]+: VOXLINK_CHECK\\(width > 4\\) failed\n");
}

TEST(CheckDeathTest, ComparisonsPrintBothOperands) {
  const int width = 3, height = 4;
  EXPECT_DEATH(VOXLINK_CHECK_EQ(width, height),
               "check_test.cpp:[0-9]+: VOXLINK_CHECK_EQ\\(width, height\\) failed: "
               "width = 3, height = 4");
  const uint64_t index = 7, size = 7;
  EXPECT_DEATH(VOXLINK_CHECK_LT(index, size),
               "VOXLINK_CHECK_LT\\(index, size\\) failed: index = 7, size = 7");
  EXPECT_DEATH(VOXLINK_CHECK_NE(index, size), "VOXLINK_CHECK_NE\\(index, size\\) failed");
  EXPECT_DEATH(VOXLINK_CHECK_LE(size + 1, index),
               "VOXLINK_CHECK_LE\\(size \\+ 1, index\\) failed: size \\+ 1 = 8, index = 7");
  EXPECT_DEATH(VOXLINK_CHECK_GT(0.5, 1.5), "failed: 0.5 = 0.5, 1.5 = 1.5");
  const uint8_t brick = 9;  // char-sized numbers print as numbers
  EXPECT_DEATH(VOXLINK_CHECK_GE(brick, 16), "brick = 9, 16 = 16");
  const std::string name = "x.vxl";
  EXPECT_DEATH(VOXLINK_CHECK_EQ(name, std::string("y.vxl")), "name = x.vxl");
}

TEST(Check, IntegersCompareByValueWhateverTheirSignedness) {
  // -1 < 0u is false in plain C++ (the -1 converts to a huge unsigned); the check means the value.
  const int minusOne = -1;
  const unsigned zero = 0;
  VOXLINK_CHECK_LT(minusOne, zero);
  VOXLINK_CHECK_NE(minusOne, 4294967295u);
  EXPECT_DEATH(VOXLINK_CHECK_GE(minusOne, zero), "minusOne = -1, zero = 0");
}

TEST(Check, DebugChecksEvaluateNothingInReleaseBuilds) {
  int evaluated = 0;
  const auto count = [&evaluated] { return ++evaluated; };
  VOXLINK_DCHECK(count() > 0);
  VOXLINK_DCHECK_NE(count(), 0);
  VOXLINK_DCHECK_LT(count(), 1000);
#ifdef NDEBUG
  EXPECT_EQ(evaluated, 0);
#else
  EXPECT_EQ(evaluated, 3);
#endif
}

TEST(CheckDeathTest, DebugChecksFailOnlyInDebugBuilds) {
#ifdef NDEBUG
  VOXLINK_DCHECK_EQ(1, 2);
  VOXLINK_DCHECK(false, "never evaluated");
#else
  EXPECT_DEATH(VOXLINK_DCHECK_EQ(1, 2), "VOXLINK_CHECK_EQ\\(1, 2\\) failed: 1 = 1, 2 = 2");
#endif
}

TEST(CheckDeathTest, ErrorOfAnOkStatusAborts) {
  const Status ok = Status::ok();
  EXPECT_DEATH((void)ok.error(), "Status::error\\(\\) called on an OK status");
  EXPECT_DEATH((void)ok.message(), "Status::error\\(\\) called on an OK status");
}

TEST(CheckDeathTest, ResultFromAnOkStatusAborts) {
  EXPECT_DEATH((void)Result<int>(Status::ok()), "Result built from an OK Status");
}

TEST(Check, PassingChecksAndFailedStatusesRunOn) {
  VOXLINK_CHECK(1 + 1 == 2, "arithmetic");
  const Status failed = makeError(ErrorCode::kCorrupt, "x.vxl: bad");
  EXPECT_EQ(failed.message(), "x.vxl: bad");
  const Result<int> r = failed;
  EXPECT_EQ(r.code(), ErrorCode::kCorrupt);
}

}  // namespace
}  // namespace voxlink
