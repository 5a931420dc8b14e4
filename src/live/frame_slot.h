#pragma once
// The hand-over between a camera's capture thread and its processing thread:
// one frame, latest wins. A new frame replaces one not yet taken (a drop,
// counted by the caller), so processing that falls behind never queues old
// frames. Frames are swapped, never copied: each side gets the other's
// buffer back, so after the first frames nothing is allocated.
#include <condition_variable>
#include <mutex>

#include "io/frame_source.h"

namespace dv {

class FrameSlot {
 public:
  // Puts `f` into the slot and gives `f` the slot's old buffer. Returns true
  // when that replaced a frame nobody took (a dropped frame).
  bool put(Frame& f) {
    bool dropped;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      std::swap(frame_, f);
      dropped = full_;
      full_ = true;
    }
    ready_.notify_one();
    return dropped;
  }

  // Waits at most timeout_s for a frame and swaps it into `f`. false on
  // timeout or when closed.
  bool take(Frame& f, double timeout_s) {
    std::unique_lock<std::mutex> lock(mutex_);
    ready_.wait_for(lock, std::chrono::duration<double>(timeout_s), [&] { return full_ || closed_; });
    if (!full_) return false;
    std::swap(frame_, f);
    full_ = false;
    return true;
  }

  bool empty() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return !full_;
  }
  bool closed() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return closed_;
  }

  // Wakes a waiting take(); a frame still in the slot can be taken, then
  // take() returns false at once.
  void close() {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      closed_ = true;
    }
    ready_.notify_all();
  }

 private:
  mutable std::mutex mutex_;
  std::condition_variable ready_;
  Frame frame_;
  bool full_ = false;
  bool closed_ = false;
};

}  // namespace dv
