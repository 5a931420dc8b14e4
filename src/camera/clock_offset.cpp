#include "camera/clock_offset.h"

#include <algorithm>

namespace dv {

ClockOffset::ClockOffset(double window_s, double jump_s, size_t capacity)
    : window_s_(window_s), jump_s_(jump_s), ring_(std::max<size_t>(capacity, 2)) {}

void ClockOffset::reset() { head_ = count_ = 0; }

double ClockOffset::offset() const { return count_ ? at(0).offset : 0.0; }

double ClockOffset::map(double camera_s, double arrival_s) {
  const double sample = arrival_s - camera_s;
  if (count_ && sample - at(0).offset > jump_s_) reset();  // camera clock went back
  // Samples older than the window no longer count.
  while (count_ && at(0).arrival < arrival_s - window_s_) {
    head_ = (head_ + 1) % ring_.size();
    --count_;
  }
  // Drop samples from the back that can never be the minimum again.
  while (count_ && at(count_ - 1).offset >= sample) --count_;
  if (count_ == ring_.size()) {  // full: the oldest goes
    head_ = (head_ + 1) % ring_.size();
    --count_;
  }
  at(count_) = {arrival_s, sample};
  ++count_;
  // The current sample is in the window, so the minimum is <= sample and
  // the result is never later than the arrival.
  return camera_s + at(0).offset;
}

}  // namespace dv
