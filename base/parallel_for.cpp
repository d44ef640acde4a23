// SPDX-License-Identifier: BSD-3-Clause
#include "base/parallel_for.h"

#include <pthread.h>
#include <tbb/global_control.h>

#include <condition_variable>
#include <cstdio>
#include <cstdlib>
#include <exception>
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

// Helper threads kept between calls: starting them per call cost about 23 us a call with 2
// threads and 350 us with 16 (bench/parallel_call_cost.cpp, docs/parallelism.md), and a
// `convert --slab 8` of a 1024^3 volume makes about 250 calls. A call borrows idle helpers, and
// starts new ones only while the pool holds fewer than its share (the threads one call may use,
// times the calls in flight, so several callers each get theirs and a command never sees more
// distinct threads than its limit); a thread the system refuses is left out. Helpers go back to
// the idle list when their job ends; they are never joined (idle ones sleep until the process
// ends), so the pool and its helpers are never freed.
class HelperPool {
 public:
  // Runs job(1), job(2), ... job(k) on k <= wanted helpers, one each; returns k.
  unsigned lend(unsigned wanted, const std::function<void(unsigned)>& job) {
    std::lock_guard lock(mutex_);
    const unsigned share = wanted * ++callsInFlight_;
    unsigned lent = 0;
    for (; lent < wanted && !idle_.empty(); ++lent) {
      Helper* helper = idle_.back();
      idle_.pop_back();
      helper->job = [job, t = lent + 1] { job(t); };
      helper->wake.notify_one();
    }
    for (; lent < wanted && started_ < share; ++lent) {
      auto* helper = new Helper;
      helper->job = [job, t = lent + 1] { job(t); };
      try {
        std::thread([this, helper] { serve(helper); }).detach();
      } catch (const std::system_error&) {  // no thread to spare: the others do its share
        delete helper;
        break;
      }
      ++started_;
    }
    return lent;
  }

  // The caller's side of lend() is over (its helpers may still be finishing).
  void callEnded() {
    std::lock_guard lock(mutex_);
    --callsInFlight_;
  }

 private:
  struct Helper {
    std::condition_variable wake;
    std::function<void()> job;  // empty while idle
  };

  void serve(Helper* self) {
    std::unique_lock lock(mutex_);
    for (;;) {
      self->wake.wait(lock, [self] { return bool(self->job); });
      std::function<void()> job = std::move(self->job);
      self->job = nullptr;
      lock.unlock();
      job();
      job = nullptr;  // what it holds is released outside the lock
      lock.lock();
      idle_.push_back(self);
    }
  }

  std::mutex mutex_;
  std::vector<Helper*> idle_;
  unsigned started_ = 0, callsInFlight_ = 0;
};

// A child forked while helpers exist has none of them (only the forking thread survives, and the
// pool's lock may be held): it starts over with an empty pool.
HelperPool*& poolSlot() {
  static HelperPool* pool = [] {
    pthread_atfork(nullptr, nullptr, [] { poolSlot() = new HelperPool; });
    return new HelperPool;
  }();
  return pool;
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
  if (threads <= 1) {
    WorkerScope scope;
    work(0);
    return;
  }
  // A helper enters only while the gate is open: the caller closes it once its own work(0) is
  // done (the items are all taken then) and waits for those inside, not for helpers that the
  // scheduler has not run yet (on a loaded machine that wait was milliseconds per loop). A late
  // helper sees the gate closed and goes back to the pool without touching the caller's stack.
  struct Gate {
    std::mutex mutex;
    std::condition_variable left;
    bool closed = false;
    unsigned inside = 0;
    std::exception_ptr failure;  // the first exception a work(t) threw, rethrown to the caller
  };
  const auto gate = std::make_shared<Gate>();
  HelperPool& pool = *poolSlot();
  pool.lend(threads - 1, [gate, &work](unsigned t) {
    {
      std::lock_guard lock(gate->mutex);
      if (gate->closed) return;
      ++gate->inside;
    }
    std::exception_ptr failure;
    try {
      WorkerScope scope;
      work(t);
    } catch (...) {  // escaping a helper would end the process; the caller rethrows it
      failure = std::current_exception();
    }
    std::lock_guard lock(gate->mutex);
    if (failure && !gate->failure) gate->failure = failure;
    if (--gate->inside == 0) gate->left.notify_all();
  });
  // Whatever work(0) does, the caller closes the gate and waits: helpers inside still use `work`
  // and the caller's stack, and the pool counts this call until callEnded().
  std::exception_ptr failure;
  try {
    WorkerScope scope;
    work(0);
  } catch (...) {
    failure = std::current_exception();
  }
  std::unique_lock lock(gate->mutex);
  gate->closed = true;
  gate->left.wait(lock, [&] { return gate->inside == 0; });
  if (!failure) failure = gate->failure;
  lock.unlock();
  pool.callEnded();
  if (failure) std::rethrow_exception(failure);
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
