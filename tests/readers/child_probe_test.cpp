// SPDX-License-Identifier: BSD-3-Clause
// probeInChild (sources/readers/detail/child_probe.h): a crash in the child is seen as a crash even
// when the parent has crash handlers of its own that would exit instead (libFuzzer, crash
// reporters).
#include "sources/readers/detail/child_probe.h"

#include <gtest/gtest.h>
#include <signal.h>
#include <unistd.h>

#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#if defined(__has_feature)
#if __has_feature(address_sanitizer) && !defined(__SANITIZE_ADDRESS__)
#define __SANITIZE_ADDRESS__ 1
#endif
#endif

extern "C" void __sanitizer_set_death_callback(void (*callback)(void)) __attribute__((weak));

namespace voxlink::sources {

namespace {

void exitQuietly(int) { _exit(3); }

TEST(ProbeInChild, ChildAbortIsADeathEvenWithTheParentsAbortHandler) {
  struct sigaction mine {
  }, previous{};
  mine.sa_handler = exitQuietly;
  sigemptyset(&mine.sa_mask);
  ASSERT_EQ(sigaction(SIGABRT, &mine, &previous), 0);
  const ProbeOutcome outcome = probeInChild([](const MarkFn& mark) {
    mark(7);
    std::abort();
  });
  sigaction(SIGABRT, &previous, nullptr);
  EXPECT_TRUE(outcome.died);
  EXPECT_EQ(outcome.signal, SIGABRT);
  ASSERT_TRUE(outcome.lastMark.has_value());
  EXPECT_EQ(*outcome.lastMark, 7u);
}

TEST(ProbeInChild, ChildThatExitsWithAFailureStatusDied) {
  // What a sanitizer's report does in the child: print and exit with status 1.
  const ProbeOutcome outcome = probeInChild([](const MarkFn& mark) {
    mark(2);
    _exit(1);
  });
  EXPECT_TRUE(outcome.died);
  EXPECT_EQ(outcome.signal, 0);
  EXPECT_EQ(outcome.exitStatus, 1);
  EXPECT_EQ(describeDeath(outcome), "exit status 1");
}

TEST(ProbeInChild, ChildThatFinishesSurvives) {
  const ProbeOutcome outcome = probeInChild([](const MarkFn& mark) { mark(1); });
  EXPECT_FALSE(outcome.died);
  EXPECT_FALSE(outcome.thrown.has_value());
}

TEST(ProbeInChild, MemoryBoundStopsAHugeAllocation) {
  // 8 GiB against a 256 MiB allowance: refused in the child, the parent untouched.
  const ProbeOutcome outcome = probeInChild(
      [](const MarkFn& mark) {
        mark(4);
        std::vector<char> huge(size_t{8} << 30);
        huge[huge.size() - 1] = 1;
        if (huge.back() != 1) std::abort();
      },
      uint64_t{256} << 20);
  EXPECT_TRUE(outcome.died || outcome.thrown.has_value());
  ASSERT_TRUE(outcome.lastMark.has_value());
  EXPECT_EQ(*outcome.lastMark, 4u);
  // Within the allowance the same work finishes.
  const ProbeOutcome small = probeInChild(
      [](const MarkFn&) {
        std::vector<char> buffer(size_t{64} << 20, 1);
        if (buffer.back() != 1) std::abort();
      },
      uint64_t{256} << 20);
  EXPECT_FALSE(small.died);
  EXPECT_FALSE(small.thrown.has_value());
}

#if defined(__SANITIZE_ADDRESS__)
std::string deathMarker;  // the file the parent's death callback would create
void markDeath() { std::ofstream(deathMarker) << "parent's death callback ran in the child\n"; }
#endif

TEST(ProbeInChild, ParentsSanitizerDeathCallbackDoesNotRunInTheChild) {
  // libFuzzer's callback saves the current input as a crash; a sanitizer report in the child
  // (a library's bad read, or its out-of-memory stop under the memory bound) is the guard
  // working, not a crash of the parent.
#if defined(__SANITIZE_ADDRESS__)
  deathMarker = (std::filesystem::path(::testing::TempDir()) / "child_probe_death_marker").string();
  std::filesystem::remove(deathMarker);
  __sanitizer_set_death_callback(markDeath);
  const ProbeOutcome outcome = probeInChild([](const MarkFn&) {
    std::vector<char> buffer(16);
    volatile size_t past = buffer.size();
    buffer.data()[past] = 1;  // heap-buffer-overflow: AddressSanitizer reports and exits
  });
  __sanitizer_set_death_callback(nullptr);
  EXPECT_TRUE(outcome.died);
  EXPECT_FALSE(std::filesystem::exists(deathMarker)) << "the child ran the parent's callback";
#else
  GTEST_SKIP() << "needs AddressSanitizer";
#endif
}

}  // namespace
}  // namespace voxlink::sources
