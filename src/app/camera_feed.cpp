#include "app/camera_feed.h"

#include <chrono>

#include "app/camera_processor.h"

namespace dv::app {

namespace {
int64_t steadyMs() {
  return std::chrono::duration_cast<std::chrono::milliseconds>(std::chrono::steady_clock::now().time_since_epoch())
      .count();
}
constexpr int64_t kDetectionsWantedMs = 3000;
}  // namespace

void CameraFeed::onFrame(const Frame& frame, const ssl::SSL_WrapperPacket& packet, const CameraProcessor* processor) {
  if (processor && colors_wanted_until_ms_.load(std::memory_order_relaxed) > steadyMs()) {
    std::lock_guard<std::mutex> lock(mutex_);
    if (colors_.blobs.capacity() < kBlobRing) colors_.blobs.reserve(kBlobRing);  // once
    processor->detector().classColors(colors_.classes);
    colors_.separations = processor->detector().colorSeparations();
    for (const Blob& b : processor->blobs().blobs) {
      const BlobColor c{colorFeature(b.rgb[0], b.rgb[1], b.rgb[2]), b.score};
      if (colors_.blobs.size() < kBlobRing) {
        colors_.blobs.push_back(c);
      } else {
        colors_.blobs[ring_next_] = c;
        ring_next_ = (ring_next_ + 1) % kBlobRing;
      }
    }
    have_colors_ = true;
  }
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
      frame_setup_.known = processor != nullptr;
      if (processor) {  // plain structs: no allocation
        frame_setup_.calibration = processor->camera().calibration();
        frame_setup_.pipeline = processor->pipeline().options();
      }
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

bool CameraFeed::snapshot(double timeout_s, Frame& frame, ssl::SSL_DetectionFrame& detection, bool& fresh,
                          Setup* setup) {
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
  if (setup) *setup = frame_setup_;
  return true;
}

bool CameraFeed::colors(Colors& out) {
  colors_wanted_until_ms_.store(steadyMs() + kDetectionsWantedMs, std::memory_order_relaxed);
  std::lock_guard<std::mutex> lock(mutex_);
  if (!have_colors_) return false;
  for (int i = 0; i < Detector::kClassColorCount; ++i) out.classes[i] = colors_.classes[i];
  out.separations = colors_.separations;
  // Oldest first: the ring from where the next one goes.
  const size_t n = colors_.blobs.size();
  out.blobs.clear();
  for (size_t i = 0; i < n; ++i) out.blobs.push_back(colors_.blobs[(ring_next_ + i) % n]);
  return true;
}

}  // namespace dv::app
