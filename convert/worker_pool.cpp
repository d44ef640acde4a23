#include "convert/worker_pool.h"

#include <system_error>

#include "format/parallel_for.h"

namespace voxlink::convert {

WorkerPool::WorkerPool(unsigned threads) {
  threads = format::threadCount(threads);
  // A thread the system cannot start (task or address-space limits) is left out: the pool runs
  // with those that did start (size() says how many), instead of aborting the program.
  for (unsigned i = 1; i < threads; ++i) {
    try {
      workers_.emplace_back([this, i] { loop(i); });
    } catch (const std::system_error&) {
      break;
    }
  }
}

WorkerPool::~WorkerPool() {
  {
    std::lock_guard lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  for (std::thread& t : workers_) t.join();
}

void WorkerPool::work(unsigned worker) {
  for (;;) {
    size_t i;
    {
      std::lock_guard lock(mutex_);
      if (next_ >= count_) return;
      i = next_++;
    }
    (*job_)(i, worker);
    {
      std::lock_guard lock(mutex_);
      if (++finished_ == count_) done_.notify_all();
    }
  }
}

void WorkerPool::loop(unsigned worker) {
  unsigned seen = 0;
  for (;;) {
    {
      std::unique_lock lock(mutex_);
      wake_.wait(lock, [&] { return stop_ || generation_ != seen; });
      if (stop_) return;
      seen = generation_;
    }
    work(worker);
  }
}

void WorkerPool::run(size_t count, const std::function<void(size_t, unsigned)>& job) {
  if (count == 0) return;
  {
    std::lock_guard lock(mutex_);
    job_ = &job;
    count_ = count;
    next_ = 0;
    finished_ = 0;
    ++generation_;
  }
  wake_.notify_all();
  work(0);
  std::unique_lock lock(mutex_);
  done_.wait(lock, [&] { return finished_ == count_; });
  job_ = nullptr;
}

}  // namespace voxlink::convert
