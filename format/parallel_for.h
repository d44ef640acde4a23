// Runs fn(i) for i in [0, count) on up to `threads` threads (0: every core), handing out indices
// one at a time, so uneven items balance. The format library's only threading; it has no
// dependency on the converter's worker pool.
#pragma once

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <functional>
#include <system_error>
#include <thread>
#include <vector>

#include "format/error.h"
#include "format/limits.h"

namespace voxlink::format {

using limits::kMaxThreads;

// Refuses a thread count above kMaxThreads (format/limits.h); `option` names it in the error.
inline Status checkThreadCount(unsigned threads, const char* option) {
  if (threads > kMaxThreads)
    return makeError(ErrorCode::kInvalidArgument, option, " ", threads, " is more than ",
                     kMaxThreads, " threads (0: every core)");
  return Status::ok();
}

// The threads that `threads` asks for: itself, or every core for 0; never more than
// kMaxThreads, whatever a caller that did not check passes.
inline unsigned threadCount(unsigned threads) {
  return std::min(kMaxThreads,
                  threads ? threads : std::max(1u, std::thread::hardware_concurrency()));
}

// Runs work(t) on the calling thread (t = 0) and on up to threads - 1 more (t = 1, 2, ...), and
// waits for all of them. A thread the system cannot start (a task or address-space limit, as on
// a shared node or in a container) is left out and the ones already running do its share, so
// `work` must take its items from a shared counter, never decide them by t.
template <class Work>
void runOnThreads(unsigned threads, Work&& work) {
  std::vector<std::thread> pool;
  struct JoinAll {
    std::vector<std::thread>& pool;
    ~JoinAll() {
      for (std::thread& t : pool) t.join();
    }
  } joinAll{pool};
  for (unsigned t = 1; t < threads; ++t) {
    try {
      pool.emplace_back(std::ref(work), t);
    } catch (const std::system_error&) {
      break;
    }
  }
  work(0u);
}

template <class Fn>
void parallelFor(uint64_t count, unsigned threads, Fn&& fn) {
  std::atomic<uint64_t> next{0};
  runOnThreads(static_cast<unsigned>(std::min<uint64_t>(threadCount(threads), count)),
               [&](unsigned) {
                 for (uint64_t i = next.fetch_add(1); i < count; i = next.fetch_add(1)) fn(i);
               });
}

}  // namespace voxlink::format
