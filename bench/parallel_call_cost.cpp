// SPDX-License-Identifier: BSD-3-Clause
// What one base::parallelFor call costs when its work is tiny (docs/parallelism.md): CALLS calls
// of `threads` items of almost nothing, against the same calls on an engine that starts its
// helper threads per call (the facility's engine before its pool; copied here as the peer, so
// both are timed in the same run), and one thread doing the items itself. Rounds alternate the
// three; prints each round's microseconds per call, the medians, and the share of items the
// helpers took (helpers the scheduler runs late get none).
//   voxlink_bench_parallel_call_cost [CALLS] [THREADS] [ROUNDS]
#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <memory>
#include <mutex>
#include <system_error>
#include <thread>
#include <vector>

#include "base/parallel_for.h"

namespace {

// The engine of base/parallel_for.cpp before it kept its threads (commit 464fbb9): detached
// helpers started per call, a gate the caller closes after its own share.
void runOnThreadsStartedPerCall(unsigned threads, const std::function<void(unsigned)>& work) {
  struct Gate {
    std::mutex mutex;
    std::condition_variable left;
    bool closed = false;
    unsigned inside = 0;
  };
  const auto gate = std::make_shared<Gate>();
  for (unsigned t = 1; t < threads; ++t) {
    try {
      std::thread([gate, &work, t] {
        {
          std::lock_guard lock(gate->mutex);
          if (gate->closed) return;
          ++gate->inside;
        }
        work(t);
        std::lock_guard lock(gate->mutex);
        if (--gate->inside == 0) gate->left.notify_all();
      }).detach();
    } catch (const std::system_error&) {
      break;
    }
  }
  work(0);
  std::unique_lock lock(gate->mutex);
  gate->closed = true;
  gate->left.wait(lock, [&] { return gate->inside == 0; });
}

struct Timing {
  double microsPerCall = 0;
  double helperShare = 0;  // items taken by threads other than the caller
};

// `calls` loops of `threads` items through `run`; each item spins about a microsecond.
template <class Run>
Timing timeCalls(unsigned calls, unsigned threads, Run run) {
  std::atomic<uint64_t> byHelpers{0};
  const auto start = std::chrono::steady_clock::now();
  for (unsigned c = 0; c < calls; ++c) {
    std::atomic<uint64_t> next{0};
    run(threads, [&](unsigned t) {
      for (uint64_t i = next.fetch_add(1); i < threads; i = next.fetch_add(1)) {
        volatile uint64_t sink = 0;
        for (int k = 0; k < 300; ++k) sink = sink + static_cast<uint64_t>(k);
        if (t != 0) byHelpers.fetch_add(1, std::memory_order_relaxed);
      }
    });
  }
  const std::chrono::duration<double, std::micro> took = std::chrono::steady_clock::now() - start;
  return {took.count() / calls, double(byHelpers) / (double(calls) * threads)};
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
  const unsigned calls = argc > 1 ? unsigned(std::atoi(argv[1])) : 2000;
  const unsigned threads = argc > 2 ? unsigned(std::atoi(argv[2])) : 2;
  const unsigned rounds = argc > 3 ? unsigned(std::atoi(argv[3])) : 7;
  if (calls == 0 || threads < 2 || rounds == 0) {
    std::fprintf(stderr, "usage: %s [CALLS > 0] [THREADS >= 2] [ROUNDS > 0]\n", argv[0]);
    return 2;
  }
  const voxlink::ThreadLimit limit(threads);
  std::vector<double> facility, perCall, serial, facilityShare, perCallShare;
  std::printf("%-6s %14s %14s %14s %12s %12s\n", "round", "facility_us", "per_call_us",
              "one_thread_us", "fac_helpers", "pc_helpers");
  for (unsigned r = 1; r <= rounds; ++r) {
    const Timing f = timeCalls(
        calls, threads,
        [](unsigned n, const std::function<void(unsigned)>& w) { voxlink::runOnThreads(n, w); });
    const Timing p = timeCalls(calls, threads, runOnThreadsStartedPerCall);
    const Timing s =
        timeCalls(calls, threads, [](unsigned, const std::function<void(unsigned)>& w) { w(0); });
    std::printf("%-6u %14.2f %14.2f %14.2f %11.0f%% %11.0f%%\n", r, f.microsPerCall,
                p.microsPerCall, s.microsPerCall, 100 * f.helperShare, 100 * p.helperShare);
    facility.push_back(f.microsPerCall);
    perCall.push_back(p.microsPerCall);
    serial.push_back(s.microsPerCall);
    facilityShare.push_back(f.helperShare);
    perCallShare.push_back(p.helperShare);
  }
  std::printf(
      "median us per call (%u threads, %u calls a round): facility %.2f, threads started per "
      "call %.2f, one thread %.2f; helpers' share of items: facility %.0f %%, per call %.0f %%\n",
      threads, calls, median(facility), median(perCall), median(serial),
      100 * median(facilityShare), 100 * median(perCallShare));
  return 0;
}
