#include "live/raw_ring.h"

#include <algorithm>

namespace dv {

namespace {
constexpr double kMaxFps = 75;  // slots for `seconds` at the fastest camera the league uses
}

void RawRing::add(const Frame& f, const std::string& packet) {
  std::lock_guard<std::mutex> lock(mutex_);
  if (slots_.empty()) {
    const size_t frame_bytes = std::max<size_t>(1, f.image.total() * f.image.elemSize());
    const size_t by_time = static_cast<size_t>(seconds_ * kMaxFps) + 1;
    slots_.resize(std::max<size_t>(1, std::min(by_time, max_bytes_ / frame_bytes)));
  }
  Entry& e = slots_[next_];
  f.image.copyTo(e.image);  // reuses the slot's buffer once the ring is full
  e.format = f.format;
  e.index = f.index;
  e.t_capture = f.t_capture;
  e.packet.assign(packet);
  next_ = (next_ + 1) % slots_.size();
  count_ = std::min(count_ + 1, slots_.size());
}

std::vector<RawRing::Entry> RawRing::snapshot() const {
  std::lock_guard<std::mutex> lock(mutex_);
  std::vector<Entry> out;
  if (count_ == 0) return out;
  const size_t first = (next_ + slots_.size() - count_) % slots_.size();
  const double newest = slots_[(next_ + slots_.size() - 1) % slots_.size()].t_capture;
  for (size_t k = 0; k < count_; ++k) {
    const Entry& e = slots_[(first + k) % slots_.size()];
    if (newest - e.t_capture > seconds_) continue;
    Entry copy;
    e.image.copyTo(copy.image);
    copy.format = e.format;
    copy.index = e.index;
    copy.t_capture = e.t_capture;
    copy.packet = e.packet;
    out.push_back(std::move(copy));
  }
  return out;
}

}  // namespace dv
