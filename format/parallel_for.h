// Runs fn(i) for i in [0, count) on up to `threads` threads (0: every core), handing out indices
// one at a time, so uneven items balance. The format library's only threading; it has no
// dependency on the converter's worker pool.
#pragma once

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <thread>
#include <vector>

namespace voxlink::format {

// The threads that `threads` asks for: itself, or every core for 0.
inline unsigned threadCount(unsigned threads) {
  return threads ? threads : std::max(1u, std::thread::hardware_concurrency());
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
