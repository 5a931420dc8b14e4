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

  // Calls fn(begin, end) on disjoint ranges covering [0, n), one range per
  // thread (the caller takes one). Blocks until every range is done.
  template <class F>
  void parallelFor(int n, F&& fn) {
    if (n <= 0) return;
    const int parts = n < size_ ? n : size_;
    if (parts == 1) {
      fn(0, n);
      return;
    }
    auto* f = &fn;
    run(parts, n, [](void* ctx, int b, int e) { (*static_cast<decltype(f)>(ctx))(b, e); }, f);
  }

 private:
  using Job = void (*)(void*, int, int);
  void run(int parts, int n, Job job, void* ctx);
  void workerLoop(int index);
  void doPart(int part);

  int size_ = 1;
  std::vector<std::thread> workers_;
  std::mutex mutex_;
  std::condition_variable wake_;
  std::condition_variable done_cv_;
  // Current job; generation_ changes when a new one is posted.
  Job job_ = nullptr;
  void* ctx_ = nullptr;
  int parts_ = 0, n_ = 0;
  unsigned long generation_ = 0;
  std::atomic<int> remaining_{0};
  bool stop_ = false;
};

}  // namespace dv
