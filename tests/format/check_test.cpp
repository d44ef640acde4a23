// VOXLINK_CHECK holds in release builds: misusing Status or Result stops the process with a
// message instead of reading an empty optional.
#include "format/check.h"

#include <gtest/gtest.h>

#include "format/error.h"

namespace voxlink {
namespace {

TEST(CheckDeathTest, FailedCheckAbortsWithTheCondition) {
  EXPECT_DEATH(VOXLINK_CHECK(1 + 1 == 3, "arithmetic"),
               "VOXLINK_CHECK\\(1 \\+ 1 == 3\\) failed: arithmetic");
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
