#include "pipeline/thread_pool.h"

#if defined(__linux__)
#include <sched.h>
#endif

namespace dv {

namespace {

// Cores this process may run on (taskset, cgroups), which
// hardware_concurrency() ignores.
int usableCores() {
#if defined(__linux__)
  cpu_set_t set;
  if (sched_getaffinity(0, sizeof(set), &set) == 0) return CPU_COUNT(&set);
#endif
  return static_cast<int>(std::thread::hardware_concurrency());
}

}  // namespace

ThreadPool::ThreadPool(int threads) {
  size_ = threads > 0 ? threads : usableCores();
  if (size_ < 1) size_ = 1;
  for (int i = 1; i < size_; ++i) workers_.emplace_back([this, i] { workerLoop(i); });
}

ThreadPool::~ThreadPool() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  for (auto& t : workers_) t.join();
}

void ThreadPool::doPart(int part) {
  const long b = static_cast<long>(n_) * part / parts_;
  const long e = static_cast<long>(n_) * (part + 1) / parts_;
  job_(ctx_, static_cast<int>(b), static_cast<int>(e));
}

void ThreadPool::run(int parts, int n, Job job, void* ctx) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    job_ = job;
    ctx_ = ctx;
    parts_ = parts;
    n_ = n;
    remaining_.store(parts - 1, std::memory_order_relaxed);
    ++generation_;
  }
  wake_.notify_all();
  doPart(0);
  // Short spin first: the other parts usually finish within microseconds.
  for (int i = 0; i < 20000 && remaining_.load(std::memory_order_acquire) > 0; ++i) {
#if defined(__x86_64__)
    __builtin_ia32_pause();
#endif
  }
  if (remaining_.load(std::memory_order_acquire) > 0) {
    std::unique_lock<std::mutex> lock(mutex_);
    done_cv_.wait(lock, [this] { return remaining_.load(std::memory_order_acquire) == 0; });
  }
}

void ThreadPool::workerLoop(int index) {
  unsigned long seen = 0;
  for (;;) {
    {
      std::unique_lock<std::mutex> lock(mutex_);
      wake_.wait(lock, [&] { return stop_ || generation_ != seen; });
      if (stop_) return;
      seen = generation_;
    }
    if (index < parts_) {
      doPart(index);
      if (remaining_.fetch_sub(1, std::memory_order_acq_rel) == 1) {
        std::lock_guard<std::mutex> lock(mutex_);
        done_cv_.notify_all();
      }
    }
  }
}

}  // namespace dv
