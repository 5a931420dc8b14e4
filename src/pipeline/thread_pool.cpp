#include "pipeline/thread_pool.h"

#include <chrono>

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

inline void cpuRelax() {
#if defined(__x86_64__)
  __builtin_ia32_pause();
#endif
}

// Ranges per thread: enough that a thread the OS delays only holds back a
// small part of the stage, few enough that a range stays a long stream.
constexpr int kChunksPerThread = 4;
// A frame's stages follow each other within microseconds; a worker that
// keeps polling this long after a job catches the next one without the
// sleep/wake-up latency of the condition variable, and sleeps between frames.
constexpr auto kSpinAfterJob = std::chrono::microseconds(200);

}  // namespace

ThreadPool::ThreadPool(int threads) {
  size_ = threads > 0 ? threads : usableCores();
  if (size_ < 1) size_ = 1;
  for (int i = 1; i < size_; ++i) workers_.emplace_back([this] { workerLoop(); });
}

ThreadPool::~ThreadPool() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
    generation_.fetch_add(1, std::memory_order_release);
  }
  wake_.notify_all();
  for (auto& t : workers_) t.join();
}

void ThreadPool::takeChunks() {
  for (;;) {
    const int c = next_chunk_.fetch_add(1, std::memory_order_relaxed);
    if (c >= chunks_) return;
    const long b = static_cast<long>(n_) * c / chunks_;
    const long e = static_cast<long>(n_) * (c + 1) / chunks_;
    job_(ctx_, static_cast<int>(b), static_cast<int>(e));
  }
}

void ThreadPool::run(int n, Job job, void* ctx) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    job_ = job;
    ctx_ = ctx;
    n_ = n;
    chunks_ = n < size_ * kChunksPerThread ? n : size_ * kChunksPerThread;
    next_chunk_.store(0, std::memory_order_relaxed);
    const unsigned long g = generation_.load(std::memory_order_relaxed) + 1;
    entry_.store(static_cast<unsigned long long>(g & 0xffffffffu) << 32, std::memory_order_relaxed);
    generation_.store(g, std::memory_order_release);
  }
  wake_.notify_all();
  takeChunks();
  // No chunk is left: close the job to latecomers, then wait for the workers
  // that joined it (usually done within microseconds) before the next job
  // is posted.
  const auto joined = [this] { return entry_.load(std::memory_order_acquire) & kJoinedMask; };
  entry_.fetch_or(kClosed, std::memory_order_acq_rel);
  for (int i = 0; i < 20000 && joined() > 0; ++i) cpuRelax();
  if (joined() > 0) {
    std::unique_lock<std::mutex> lock(mutex_);
    done_cv_.wait(lock, [&] { return joined() == 0; });
  }
}

bool ThreadPool::join(unsigned long g) {
  unsigned long long e = entry_.load(std::memory_order_acquire);
  for (;;) {
    if ((e >> 32) != (g & 0xffffffffu) || (e & kClosed)) return false;
    if (entry_.compare_exchange_weak(e, e + 1, std::memory_order_acq_rel, std::memory_order_acquire)) return true;
  }
}

void ThreadPool::workerLoop() {
  unsigned long seen = 0;
  for (;;) {
    unsigned long g = generation_.load(std::memory_order_acquire);
    if (g == seen) {
      const auto until = std::chrono::steady_clock::now() + kSpinAfterJob;
      for (int i = 1; g == seen; ++i) {
        cpuRelax();
        g = generation_.load(std::memory_order_acquire);
        if (i % 64 == 0 && std::chrono::steady_clock::now() > until) break;
      }
    }
    {
      std::unique_lock<std::mutex> lock(mutex_);
      wake_.wait(lock, [&] { return stop_ || generation_.load(std::memory_order_relaxed) != seen; });
      if (stop_) return;
      seen = generation_.load(std::memory_order_relaxed);
    }
    // A job already closed (the caller did every chunk) is left alone.
    if (!join(seen)) continue;
    takeChunks();
    const unsigned long long before = entry_.fetch_sub(1, std::memory_order_acq_rel);
    if ((before & kJoinedMask) == 1 && (before & kClosed)) {
      std::lock_guard<std::mutex> lock(mutex_);
      done_cv_.notify_all();
    }
  }
}

}  // namespace dv
