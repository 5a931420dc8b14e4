#pragma once
// Maps a camera's own clock to the host's wall clock. Each frame gives one
// sample offset = arrival - camera time = true offset + transport delay; the
// delay is never negative and its smallest values are the closest to the
// true offset, so the estimate is the minimum over a sliding time window.
// The window follows slow drift between the two clocks; a jump of the
// camera clock (camera restarted, clock reset) starts the window afresh.
#include <cstddef>
#include <vector>

namespace dv {

class ClockOffset {
 public:
  // window_s: how far back samples count; jump_s: a sample this much above
  // the current minimum is taken as a clock jump, not as delay.
  explicit ClockOffset(double window_s = 5.0, double jump_s = 1.0, size_t capacity = 2048);

  // Adds the sample (camera time, arrival time, both s) and returns the
  // capture time on the host clock: camera time + offset estimate. Never
  // later than `arrival`; strictly increasing when camera time is.
  // No allocation.
  double map(double camera_s, double arrival_s);

  // Forgets all samples (after a reconnect the camera clock may restart).
  void reset();

  // Current estimate (s); 0 before the first sample.
  double offset() const;
  size_t samples() const { return count_; }

 private:
  struct Sample {
    double arrival;
    double offset;
  };
  Sample& at(size_t i) { return ring_[(head_ + i) % ring_.size()]; }
  const Sample& at(size_t i) const { return ring_[(head_ + i) % ring_.size()]; }

  double window_s_, jump_s_;
  // Monotonic queue in a fixed ring: offsets increase from front to back,
  // so the front is the window's minimum.
  std::vector<Sample> ring_;
  size_t head_ = 0, count_ = 0;
};

}  // namespace dv
