#include "app/camera_feed.h"

#include <chrono>

namespace dv::app {

namespace {
int64_t steadyMs() {
  return std::chrono::duration_cast<std::chrono::milliseconds>(std::chrono::steady_clock::now().time_since_epoch())
      .count();
}
constexpr int64_t kDetectionsWantedMs = 3000;
}  // namespace

void CameraFeed::onFrame(const Frame& frame, const ssl::SSL_WrapperPacket& packet) {
  const bool want_snapshot = snapshot_waiters_.load(std::memory_order_relaxed) > 0;
  const bool want_detection =
      want_snapshot || detections_wanted_until_ms_.load(std::memory_order_relaxed) > steadyMs();
  if (!want_detection) return;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    // CopyFrom reuses the messages' storage, and copyTo the image's buffer
    // while the frame size stays: no allocation once warm.
    detection_.CopyFrom(packet.detection());
    have_detection_ = true;
    if (want_snapshot) {
      frame.image.copyTo(frame_.image);
      frame_.format = frame.format;
      frame_.t_capture = frame.t_capture;
      frame_.t_capture_camera = frame.t_capture_camera;
      frame_.t_arrival = frame.t_arrival;
      frame_.index = frame.index;
      frame_detection_.CopyFrom(packet.detection());
      ++snapshots_;
    }
  }
  if (want_snapshot) taken_.notify_all();
}

bool CameraFeed::detection(ssl::SSL_DetectionFrame& out) {
  detections_wanted_until_ms_.store(steadyMs() + kDetectionsWantedMs, std::memory_order_relaxed);
  std::lock_guard<std::mutex> lock(mutex_);
  if (!have_detection_) return false;
  out.CopyFrom(detection_);
  return true;
}

bool CameraFeed::snapshot(double timeout_s, Frame& frame, ssl::SSL_DetectionFrame& detection, bool& fresh) {
  std::unique_lock<std::mutex> lock(mutex_);
  const uint64_t before = snapshots_;
  snapshot_waiters_.fetch_add(1);
  fresh = taken_.wait_for(lock, std::chrono::duration<double>(timeout_s), [&] { return snapshots_ != before; });
  snapshot_waiters_.fetch_sub(1);
  if (snapshots_ == 0) return false;
  frame.image = frame_.image.clone();
  frame.format = frame_.format;
  frame.t_capture = frame_.t_capture;
  frame.t_capture_camera = frame_.t_capture_camera;
  frame.t_arrival = frame_.t_arrival;
  frame.index = frame_.index;
  detection.CopyFrom(frame_detection_);
  return true;
}

}  // namespace dv::app
