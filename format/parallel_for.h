// Runs fn(i) for i in [0, count) on up to `threads` threads (0: every core), handing out indices
// one at a time, so uneven items balance. The format library's only threading; it has no
// dependency on the converter's worker pool.
#pragma once

#include <algorithm>
#include <atomic>
#include <cstdint>
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

template <class Fn>
void parallelFor(uint64_t count, unsigned threads, Fn&& fn) {
  threads = threadCount(threads);
  std::atomic<uint64_t> next{0};
  auto work = [&] {
    for (uint64_t i = next.fetch_add(1); i < count; i = next.fetch_add(1)) fn(i);
  };
  std::vector<std::thread> pool;
  for (unsigned t = 1; t < threads && t < count; ++t) pool.emplace_back(work);
  work();
  for (std::thread& t : pool) t.join();
}

}  // namespace voxlink::format
