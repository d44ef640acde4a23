// SPDX-License-Identifier: BSD-3-Clause
// parallelFor runs every index once; thread counts above kMaxThreads are refused by
// checkThreadCount and capped by threadCount, so a caller that skipped the check still cannot
// start tens of thousands of threads. A ThreadLimit bounds every call while it lives, nested
// calls stay on their thread, parallelSort sorts like std::sort. Helper threads are kept between
// calls (no more distinct threads than the limit however many calls), serve callers on several
// threads at once, and a forked child gets helpers of its own.
#include "base/parallel_for.h"

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <mutex>
#include <random>
#include <set>
#include <stdexcept>
#include <thread>
#include <vector>

namespace voxlink {
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

// The distinct threads that ran parallelFor's items.
template <class Run>
size_t threadsUsed(Run&& run) {
  std::mutex mutex;
  std::set<std::thread::id> ids;
  run([&] {
    std::lock_guard lock(mutex);
    ids.insert(std::this_thread::get_id());
    // Long enough that a second thread, if started, takes items too.
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  });
  return ids.size();
}

TEST(ThreadLimit, BoundsEveryCallWhileItLivesAndTheSmallestWins) {
  const auto parallel = [](unsigned threads) {
    return threadsUsed([&](auto note) { parallelFor(64, threads, [&](uint64_t) { note(); }); });
  };
  EXPECT_EQ(parallel(3), 3u);  // the check below can fail
  {
    ThreadLimit two(2);
    EXPECT_LE(threadCount(0), 2u);
    EXPECT_EQ(threadCount(8), 2u);
    {
      ThreadLimit one(1);
      EXPECT_EQ(processThreadLimit(), 1u);
      EXPECT_EQ(parallel(3), 1u);
      ThreadLimit four(4);  // a larger one later does not lift the smaller
      EXPECT_EQ(processThreadLimit(), 1u);
    }
    EXPECT_EQ(processThreadLimit(), 2u);
    EXPECT_EQ(parallel(3), 2u);
  }
  EXPECT_EQ(processThreadLimit(), kMaxThreads);
}

TEST(ParallelFor, WorkersAreNumberedBelowTheThreadCountAndNestedCallsStayOnTheirThread) {
  std::atomic<unsigned> highest{0};
  std::atomic<int> nestedOnOtherThreads{0};
  parallelFor(100, 3, [&](uint64_t, unsigned worker) {
    unsigned seen = highest.load();
    while (worker > seen && !highest.compare_exchange_weak(seen, worker)) {
    }
    const std::thread::id outer = std::this_thread::get_id();
    parallelFor(4, 4, [&](uint64_t) {
      if (std::this_thread::get_id() != outer) ++nestedOnOtherThreads;
    });
  });
  EXPECT_LT(highest.load(), 3u);
  EXPECT_EQ(nestedOnOtherThreads.load(), 0);
}

TEST(ParallelSort, SortsLikeStdSortWhateverTheThreads) {
  std::mt19937 random(7);
  for (size_t size : {0u, 1u, 1000u, 100000u, 300001u}) {
    std::vector<uint32_t> values(size);
    for (uint32_t& v : values) v = random() % 5000;  // many equal keys
    std::vector<uint32_t> expected = values;
    std::sort(expected.begin(), expected.end());
    for (unsigned threads : {1u, 2u, 3u, 7u}) {
      std::vector<uint32_t> sorted = values;
      parallelSort(sorted.begin(), sorted.end(), std::less<>(), threads);
      ASSERT_EQ(sorted, expected) << size << " " << threads;
    }
  }
}

TEST(RunInBackground, RunsOnTheCallerWithOneThreadAndElsewhereWithMore) {
  const std::thread::id caller = std::this_thread::get_id();
  auto here = runInBackground(1, [] { return std::this_thread::get_id(); });
  EXPECT_EQ(here.get(), caller);
  auto away = runInBackground(2, [] { return std::this_thread::get_id(); });
  EXPECT_NE(away.get(), caller);
  ThreadLimit one(1);
  auto limited = runInBackground(2, [] { return std::this_thread::get_id(); });
  EXPECT_EQ(limited.get(), caller);
}

// In a process whose pool is empty, with a limit of 3: 0 when a call whose items wait for each
// other gets its two helpers (three threads) and 300 calls use no more than three threads in all
// (a thread started per call would give hundreds); 1 or 2 naming which failed.
int helpersKeptBetweenCalls() {
  const ThreadLimit limit(3);
  std::mutex mutex;
  std::set<pid_t> threads;
  std::atomic<int> arrived{0};
  parallelFor(3, 3, [&](uint64_t) {
    {
      std::lock_guard lock(mutex);
      threads.insert(gettid());
    }
    ++arrived;
    const auto end = std::chrono::steady_clock::now() + std::chrono::seconds(5);
    while (arrived < 3 && std::chrono::steady_clock::now() < end) std::this_thread::yield();
  });
  if (threads.size() != 3) return 1;
  threads.clear();
  for (int call = 0; call < 300; ++call)
    parallelFor(3, 3, [&](uint64_t) {
      std::lock_guard lock(mutex);
      threads.insert(gettid());
    });
  return threads.size() <= 3 ? 0 : 2;
}

TEST(ParallelFor, HelpersAreKeptBetweenCallsAndAForkedChildGetsItsOwn) {
#if defined(__SANITIZE_ADDRESS__)
  // A child forked from a threaded process under AddressSanitizer hangs or starts no thread in
  // about two runs of three (measured: 21 of 30), the pool's own code aside; the sanitized CI
  // build leaves the fork out, as it does for the readers' child probe.
  GTEST_SKIP() << "fork from a threaded process is unreliable under AddressSanitizer";
#endif
  parallelFor(100, 4, [](uint64_t) {});  // helpers in this process now; the child has none
  const pid_t child = fork();
  if (child == 0) {
    alarm(30);  // a child that hangs dies
    _exit(helpersKeptBetweenCalls());
  }
  ASSERT_GT(child, 0);
  int status = 0;
  ASSERT_EQ(waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFEXITED(status)) << "the child died of signal " << WTERMSIG(status);
  EXPECT_NE(WEXITSTATUS(status), 1) << "a call whose items wait for each other got no helpers";
  EXPECT_NE(WEXITSTATUS(status), 2) << "300 calls used more than 3 threads";
}

TEST(ParallelFor, CallersOnSeveralThreadsEachGetEveryIndexOnce) {
  std::vector<std::thread> callers;
  std::atomic<int> wrong{0};
  for (int c = 0; c < 3; ++c)
    callers.emplace_back([&wrong] {
      for (int call = 0; call < 100; ++call) {
        std::vector<std::atomic<int>> seen(257);
        parallelFor(seen.size(), 3, [&](uint64_t i) { seen[i].fetch_add(1); });
        for (const std::atomic<int>& s : seen) wrong += s.load() != 1;
      }
    });
  for (std::thread& t : callers) t.join();
  EXPECT_EQ(wrong.load(), 0);
}

TEST(RunOnThreads, AnExceptionOnAHelperReachesTheCaller) {
  std::atomic<bool> helperStarted{false};
  bool threw = false;
  try {
    runOnThreads(2, [&](unsigned t) {
      if (t == 1) {
        helperStarted = true;
        throw std::runtime_error("helper failed");
      }
      // Give the helper time to start; one the system never runs is left out (then no throw).
      const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(10);
      while (!helperStarted && std::chrono::steady_clock::now() < until) std::this_thread::yield();
    });
  } catch (const std::runtime_error& e) {
    threw = true;
    EXPECT_STREQ(e.what(), "helper failed");
  }
  if (!helperStarted) GTEST_SKIP() << "no helper ran within 10 s on this machine";
  EXPECT_TRUE(threw);
}

TEST(RunOnThreads, AnExceptionOnTheCallerWaitsForHelpersInsideAndThePoolStaysUsable) {
  for (int call = 0; call < 50; ++call) {
    std::atomic<int> entered{0}, finished{0};
    EXPECT_THROW(runOnThreads(3,
                              [&](unsigned t) {
                                if (t == 0) throw std::logic_error("caller failed");
                                ++entered;
                                std::this_thread::sleep_for(std::chrono::milliseconds(2));
                                ++finished;
                              }),
                 std::logic_error);
    // Helpers that got in before the gate closed have finished: they used the caller's state.
    EXPECT_EQ(entered.load(), finished.load());
  }
  std::vector<std::atomic<int>> seen(1000);
  parallelFor(seen.size(), 3, [&](uint64_t i) { seen[i].fetch_add(1); });
  for (const std::atomic<int>& s : seen) EXPECT_EQ(s.load(), 1);
}

}  // namespace
}  // namespace voxlink
