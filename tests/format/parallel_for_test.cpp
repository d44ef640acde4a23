// parallelFor runs every index once; thread counts above kMaxThreads are refused by
// checkThreadCount and capped by threadCount, so a caller that skipped the check still cannot
// start tens of thousands of threads.
#include "format/parallel_for.h"

#include <gtest/gtest.h>

#include <atomic>
#include <vector>

namespace voxlink::format {
namespace {

TEST(ParallelFor, RunsEveryIndexOnceWhateverTheThreads) {
  for (unsigned threads : {0u, 1u, 3u, 64u}) {
    std::vector<std::atomic<int>> seen(1000);
    parallelFor(seen.size(), threads, [&](uint64_t i) { seen[i].fetch_add(1); });
    for (size_t i = 0; i < seen.size(); ++i) ASSERT_EQ(seen[i].load(), 1) << i << " " << threads;
  }
}

TEST(ParallelFor, ThreadCountsAboveTheLimitAreRefusedAndCapped) {
  EXPECT_TRUE(checkThreadCount(0, "--threads").isOk());
  EXPECT_TRUE(checkThreadCount(kMaxThreads, "--threads").isOk());
  const Status tooMany = checkThreadCount(kMaxThreads + 1, "--threads");
  ASSERT_FALSE(tooMany.isOk());
  EXPECT_EQ(tooMany.error().code, ErrorCode::kInvalidArgument);
  EXPECT_EQ(tooMany.error().message, "--threads 1025 is more than 1024 threads (0: every core)");
  EXPECT_EQ(threadCount(4294967295u), kMaxThreads);
  EXPECT_EQ(threadCount(3), 3u);
  EXPECT_GE(threadCount(0), 1u);
}

}  // namespace
}  // namespace voxlink::format
