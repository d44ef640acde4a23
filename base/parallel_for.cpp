// SPDX-License-Identifier: BSD-3-Clause
#include "base/parallel_for.h"

#include <tbb/global_control.h>

#include <condition_variable>
#include <cstdio>
#include <cstdlib>
#include <mutex>
#include <set>
#include <sstream>

namespace voxlink {
inline namespace base {
namespace {

// The live ThreadLimits' bounds; the smallest is the process limit, cached for the hot path.
std::mutex limitsMutex;
std::multiset<unsigned>& liveLimits() {
  static std::multiset<unsigned> limits;
  return limits;
}
std::atomic<unsigned> currentLimit{kMaxThreads};

thread_local bool workingForFacility = false;

// The test hook: VOXLINK_THREAD_CENSUS names a file that gets each working thread's id once.
class ThreadCensus {
 public:
  ThreadCensus() : path_(std::getenv("VOXLINK_THREAD_CENSUS")) {}
  void note() {
    if (!path_) return;
    const std::thread::id id = std::this_thread::get_id();
    std::lock_guard lock(mutex_);
    if (!seen_.insert(id).second) return;
    std::ostringstream line;
    line << id << '\n';
    if (FILE* f = std::fopen(path_, "a")) {
      std::fputs(line.str().c_str(), f);
      std::fclose(f);
    }
  }

 private:
  const char* path_;
  std::mutex mutex_;
  std::set<std::thread::id> seen_;
};

ThreadCensus& census() {
  static ThreadCensus c;
  return c;
}

}  // namespace

unsigned processThreadLimit() { return currentLimit.load(std::memory_order_relaxed); }

ThreadLimit::ThreadLimit(unsigned threads)
    : threads_(std::min(kMaxThreads,
                        threads ? threads : std::max(1u, std::thread::hardware_concurrency()))),
      tbbControl_(new tbb::global_control(tbb::global_control::max_allowed_parallelism, threads_)) {
  std::lock_guard lock(limitsMutex);
  liveLimits().insert(threads_);
  currentLimit.store(*liveLimits().begin());
}

ThreadLimit::~ThreadLimit() {
  {
    std::lock_guard lock(limitsMutex);
    liveLimits().erase(liveLimits().find(threads_));
    currentLimit.store(liveLimits().empty() ? kMaxThreads : *liveLimits().begin());
  }
  delete static_cast<tbb::global_control*>(tbbControl_);
}

namespace detail {

void runOnThreadsErased(unsigned threads, const std::function<void(unsigned)>& work) {
  // A helper enters only while the gate is open: the caller closes it once its own work(0) is
  // done (the items are all taken then) and waits for those inside, not for helpers that the
  // scheduler has not run yet (on a loaded machine that wait was milliseconds per loop). A late
  // helper sees the gate closed and ends without touching the caller's stack.
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
        {
          WorkerScope scope;
          work(t);
        }
        std::lock_guard lock(gate->mutex);
        if (--gate->inside == 0) gate->left.notify_all();
      }).detach();
    } catch (const std::system_error&) {
      break;
    }
  }
  {
    WorkerScope scope;
    work(0);
  }
  std::unique_lock lock(gate->mutex);
  gate->closed = true;
  gate->left.wait(lock, [&] { return gate->inside == 0; });
}

bool insideParallelWork() { return workingForFacility; }

WorkerScope::WorkerScope() : outer_(!workingForFacility) {
  workingForFacility = true;
  census().note();
}

WorkerScope::~WorkerScope() {
  if (outer_) workingForFacility = false;
}

}  // namespace detail
}  // namespace base
}  // namespace voxlink
