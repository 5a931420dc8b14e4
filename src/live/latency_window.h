#pragma once
// Times of the last minute (or the last `capacity` samples, whichever is
// fewer) for p50/p99 figures. add() is cheap and allocation-free (a fixed
// ring); percentiles are computed by whoever reads, off the hot path.
#include <algorithm>
#include <cstddef>
#include <vector>

namespace dv {

class LatencyWindow {
 public:
  explicit LatencyWindow(size_t capacity = 8192, double span_s = 60)
      : t_(capacity), v_(capacity), span_s_(span_s) {}

  // t: when (s, any monotonic clock), value: the time measured (ms).
  void add(double t, double value) {
    t_[next_] = t;
    v_[next_] = value;
    next_ = (next_ + 1) % t_.size();
    if (count_ < t_.size()) ++count_;
  }

  // Percentile q in [0, 1] of the samples taken within span_s before `now`;
  // -1 when there are none. `scratch` is the reader's buffer.
  double percentile(double now, double q, std::vector<double>& scratch) const {
    scratch.clear();
    for (size_t i = 0; i < count_; ++i)
      if (now - t_[i] <= span_s_) scratch.push_back(v_[i]);
    if (scratch.empty()) return -1;
    const size_t k = std::min(scratch.size() - 1, static_cast<size_t>(q * (scratch.size() - 1) + 0.5));
    std::nth_element(scratch.begin(), scratch.begin() + static_cast<long>(k), scratch.end());
    return scratch[k];
  }

  size_t size() const { return count_; }
  void clear() { count_ = next_ = 0; }

 private:
  std::vector<double> t_, v_;
  double span_s_;
  size_t next_ = 0, count_ = 0;
};

}  // namespace dv
