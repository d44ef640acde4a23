// SPDX-License-Identifier: BSD-3-Clause
// VoxLink's one way to run in parallel: every parallel loop, sort and background task goes
// through this header, and a process-wide limit (ThreadLimit, set once from --threads or a
// Python call's threads=) bounds all of them, TBB inside libraries included. The engine is a
// small pool of plain threads of its own, kept between calls, rather than TBB's, because TBB
// aborts the process when the system refuses a thread (ulimit -v, a task limit), and here such a
// thread is left out and the others do its share. Nested calls run on the thread that makes them,
// so a limit of N means at most N threads working at once per top-level call.
#pragma once

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <functional>
#include <future>
#include <iterator>
#include <memory>
#include <system_error>
#include <thread>
#include <type_traits>
#include <utility>
#include <vector>

#include "base/error.h"
#include "base/limits.h"

namespace voxlink {
inline namespace base {

using limits::kMaxThreads;

// Refuses a thread count above kMaxThreads (base/limits.h); `option` names it in the error.
inline Status checkThreadCount(unsigned threads, const char* option) {
  if (threads > kMaxThreads)
    return makeError(ErrorCode::kInvalidArgument, option, " ", threads, " is more than ",
                     kMaxThreads, " threads (0: every core)");
  return Status::ok();
}

// The process-wide bound every parallel path obeys: the smallest of the ThreadLimits alive now,
// or kMaxThreads when there is none.
unsigned processThreadLimit();

// Bounds every parallel path of the process to `threads` (0: every core) while it lives, TBB in
// libraries (OpenVDB, Embree) included through tbb::global_control. Commands hold one for their
// whole run; several alive at once (nested, or Python calls on two threads) bound to the
// smallest.
class ThreadLimit {
 public:
  explicit ThreadLimit(unsigned threads);
  ~ThreadLimit();
  ThreadLimit(const ThreadLimit&) = delete;
  ThreadLimit& operator=(const ThreadLimit&) = delete;

 private:
  unsigned threads_;
  void* tbbControl_;  // a tbb::global_control; TBB's headers stay out of this one
};

// The threads that `threads` asks for: itself, or every core for 0; never more than the process
// limit (kMaxThreads at most), whatever a caller that did not check passes.
inline unsigned threadCount(unsigned threads) {
  const unsigned wanted = threads ? threads : std::max(1u, std::thread::hardware_concurrency());
  return std::min({wanted, processThreadLimit(), kMaxThreads});
}

namespace detail {
// True on a thread while it runs work for this facility: a nested call runs there, serially.
bool insideParallelWork();
// Marks the calling thread as working for the facility until the guard ends. With
// VOXLINK_THREAD_CENSUS=path set, also appends the thread's id to that file the first time it
// works (tests count the distinct ids a command used).
class WorkerScope {
 public:
  WorkerScope();
  ~WorkerScope();
  WorkerScope(const WorkerScope&) = delete;
  WorkerScope& operator=(const WorkerScope&) = delete;

 private:
  bool outer_;
};
}  // namespace detail

namespace detail {
// runOnThreads without the template: lends the pool's helpers, runs work(0), waits
// (parallel_for.cpp).
void runOnThreadsErased(unsigned threads, const std::function<void(unsigned)>& work);
}  // namespace detail

// Runs work(t) on the calling thread (t = 0) and on up to threadCount(threads) - 1 more
// (t = 1, 2, ...), and waits for those that started. A thread the system cannot start (a task or
// address-space limit, as on a shared node or in a container), or one the scheduler has not run
// by the time the caller's work(0) returns, is left out and the others do its share, so `work`
// must take its items from a shared counter, never decide them by t; t may index per-thread
// scratch of threadCount(threads) entries. An exception from work(t) on any thread reaches the
// caller once every started work(t) has returned (the first one thrown, if several did).
template <class Work>
void runOnThreads(unsigned threads, Work&& work) {
  threads = detail::insideParallelWork() ? 1u : threadCount(threads);
  detail::runOnThreadsErased(threads, [&work](unsigned t) { work(t); });
}

// Runs fn(i) for i in [0, count), or fn(i, worker) with worker < threadCount(threads) naming the
// thread (for per-thread scratch), handing out indices one at a time so uneven items balance.
template <class Fn>
void parallelFor(uint64_t count, unsigned threads, Fn&& fn) {
  if (count == 0) return;
  std::atomic<uint64_t> next{0};
  runOnThreads(static_cast<unsigned>(std::min<uint64_t>(threadCount(threads), count)),
               [&](unsigned worker) {
                 for (uint64_t i = next.fetch_add(1); i < count; i = next.fetch_add(1)) {
                   if constexpr (std::is_invocable_v<Fn&, uint64_t, unsigned>)
                     fn(i, worker);
                   else
                     fn(i);
                 }
               });
}

// Sorts [first, last) by `less` like std::sort (not stable): threadCount(threads) runs sorted
// at once, then merged pairwise, the merges of a round at once.
template <class It, class Less = std::less<>>
void parallelSort(It first, It last, Less less = {}, unsigned threads = 0) {
  const uint64_t size = static_cast<uint64_t>(std::distance(first, last));
  constexpr uint64_t kSerialBelow = 1 << 14;  // smaller inputs: thread starts cost more
  const uint64_t runs = std::min<uint64_t>(threadCount(threads), size / kSerialBelow + 1);
  auto bound = [&](uint64_t r) { return first + static_cast<std::ptrdiff_t>(size * r / runs); };
  parallelFor(runs, threads, [&](uint64_t r) { std::sort(bound(r), bound(r + 1), less); });
  for (uint64_t width = 1; width < runs; width *= 2)
    parallelFor((runs + 2 * width - 1) / (2 * width), threads, [&](uint64_t pair) {
      const uint64_t lo = pair * 2 * width, mid = lo + width;
      if (mid < runs)
        std::inplace_merge(bound(lo), bound(mid), bound(std::min(runs, mid + width)), less);
    });
}

// Starts task() on a thread of its own when the limit allows a second thread and one can start;
// otherwise runs it now on the caller. Either way the future holds its result.
template <class Task>
std::future<std::invoke_result_t<Task&>> runInBackground(unsigned threads, Task task) {
  using R = std::invoke_result_t<Task&>;
  auto shared = std::make_shared<Task>(std::move(task));  // still here if no thread starts
  if (!detail::insideParallelWork() && threadCount(threads) > 1) {
    try {
      return std::async(std::launch::async, [shared]() -> R {
        detail::WorkerScope scope;
        return (*shared)();
      });
    } catch (const std::system_error&) {  // no thread to spare: run it here
    }
  }
  std::promise<R> done;
  {
    detail::WorkerScope scope;
    if constexpr (std::is_void_v<R>) {
      (*shared)();
      done.set_value();
    } else {
      done.set_value((*shared)());
    }
  }
  return done.get_future();
}

}  // namespace base
}  // namespace voxlink
