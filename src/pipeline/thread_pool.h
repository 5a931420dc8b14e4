#pragma once
// A small persistent pool for splitting one stage over the cores. Workers are
// created once; a call hands out row ranges and returns when all are done, so
// stages stay in order and nothing is allocated per frame.
#include <atomic>
#include <condition_variable>
#include <mutex>
#include <thread>
#include <vector>

namespace dv {

class ThreadPool {
 public:
  // threads: total workers including the caller; 0 = hardware concurrency.
  explicit ThreadPool(int threads);
  ~ThreadPool();
  ThreadPool(const ThreadPool&) = delete;
  ThreadPool& operator=(const ThreadPool&) = delete;

  int size() const { return size_; }

  // Calls fn(begin, end) on disjoint, contiguous ranges covering [0, n)
  // (a few per thread, taken by whichever thread is free, so a core that is
  // busy elsewhere does not hold the stage up). Blocks until every range is
  // done. With n <= size() each range is a single index.
  template <class F>
  void parallelFor(int n, F&& fn) {
    if (n <= 0) return;
    if (size_ == 1 || n == 1) {
      fn(0, n);
      return;
    }
    auto* f = &fn;
    run(n, [](void* ctx, int b, int e) { (*static_cast<decltype(f)>(ctx))(b, e); }, f);
  }

 private:
  using Job = void (*)(void*, int, int);
  void run(int n, Job job, void* ctx);
  void workerLoop();
  void takeChunks();
  // Joins job generation g unless it is closed or over; true if joined.
  bool join(unsigned long g);

  int size_ = 1;
  std::vector<std::thread> workers_;
  std::mutex mutex_;
  std::condition_variable wake_;
  std::condition_variable done_cv_;
  // Current job; generation_ changes when a new one is posted (under mutex_,
  // read without it by workers that are still spinning).
  Job job_ = nullptr;
  void* ctx_ = nullptr;
  int chunks_ = 0, n_ = 0;
  std::atomic<unsigned long> generation_{0};
  std::atomic<int> next_chunk_{0};
  // Who works on the current job: its generation (high 32 bits), a closed
  // flag and the workers that joined it (low bits). The caller closes the
  // job once it finds no chunk left and waits only for the workers that
  // joined before that, not for one the OS has not run yet (on a busy
  // machine that wait is a whole time slice).
  std::atomic<unsigned long long> entry_{0};
  static constexpr unsigned long long kClosed = 1ull << 31;
  static constexpr unsigned long long kJoinedMask = kClosed - 1;
  bool stop_ = false;
};

}  // namespace dv
