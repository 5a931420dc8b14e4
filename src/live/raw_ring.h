#pragma once
// The raw frames of a camera's last seconds, kept in memory for a bug
// report: when something goes wrong the operator (SIGUSR1) or a change of
// health writes them out with their detections, and `dotvision run` on
// that folder processes the very same frames again. Slots are filled by
// copying into buffers that, once the ring is full, are reused: no
// allocation per frame after the first lap.
#include <cstddef>
#include <cstdint>
#include <mutex>
#include <string>
#include <vector>

#include "io/frame_source.h"

namespace dv {

class RawRing {
 public:
  struct Entry {
    cv::Mat image;
    PixelFormat format = PixelFormat::Bgr8;
    uint32_t index = 0;
    double t_capture = 0;
    std::string packet;  // the detection packet sent for it (serialized SSL_WrapperPacket)
  };

  // Keeps at most `seconds` of frames and at most `max_bytes` of pixels.
  RawRing(double seconds, size_t max_bytes) : seconds_(seconds), max_bytes_(max_bytes) {}

  // On the processing thread, after the packet went out.
  void add(const Frame& f, const std::string& packet);
  // The frames within `seconds` of the newest, oldest first (copies, for a dump).
  std::vector<Entry> snapshot() const;
  size_t capacity() const { return slots_.size(); }

 private:
  double seconds_;
  size_t max_bytes_;
  mutable std::mutex mutex_;
  std::vector<Entry> slots_;
  size_t next_ = 0, count_ = 0;
};

}  // namespace dv
