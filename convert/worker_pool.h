// A fixed set of worker threads that run numbered jobs. Results must not depend on which
// thread runs which job: callers write each job's output to a place given by the job number.
#pragma once

#include <condition_variable>
#include <cstddef>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace voxlink::convert {

class WorkerPool {
 public:
  explicit WorkerPool(unsigned threads);  // 0: all hardware threads
  ~WorkerPool();
  WorkerPool(const WorkerPool&) = delete;
  WorkerPool& operator=(const WorkerPool&) = delete;

  unsigned size() const { return static_cast<unsigned>(workers_.size()) + 1; }
  // Runs job(i, worker) for i in [0, count) on all threads (the caller's included) and waits.
  // `worker` is in [0, size()) and may index per-thread scratch space.
  void run(size_t count, const std::function<void(size_t job, unsigned worker)>& job);

 private:
  void loop(unsigned worker);
  void work(unsigned worker);

  std::vector<std::thread> workers_;
  std::mutex mutex_;
  std::condition_variable wake_, done_;
  const std::function<void(size_t, unsigned)>* job_ = nullptr;
  size_t count_ = 0;
  size_t next_ = 0;
  size_t finished_ = 0;
  unsigned generation_ = 0;
  bool stop_ = false;
};

}  // namespace voxlink::convert
