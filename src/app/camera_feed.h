#pragma once
// What the console sees of one camera: its newest detection frame and, on
// request, a copy of its newest frame. onFrame() runs on the camera's
// processing thread (as CameraRunner's frame hook) and costs two relaxed
// atomic loads unless someone asked: the detection frame is copied only
// while the console polls detections (3 s after its last poll), the image
// only while a snapshot request waits. Everything else (demosaicing,
// scaling, encoding, JSON) happens on the console's threads. The same holds
// for the colors (the learned classes and a ring of recent blob colors),
// copied only while the Colors page polls them.
#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <vector>

#include "detection/detector.h"

#include "dotvision/ssl_wrapper.pb.h"
#include "geometry/camera_model.h"
#include "io/frame_source.h"
#include "pipeline/blob.h"
#include "pipeline/pipeline_options.h"

namespace dv::app {

class CameraProcessor;

class CameraFeed {
 public:
  explicit CameraFeed(uint32_t camera_id) : camera_id_(camera_id) {}
  uint32_t cameraId() const { return camera_id_; }

  // Processing thread, after each processed frame.
  // `processor`: the one that made the packet (may be null).
  void onFrame(const Frame& frame, const ssl::SSL_WrapperPacket& packet, const CameraProcessor* processor = nullptr);

  // Console threads. The newest detection frame (false: none yet); asking
  // keeps the copies coming for the next few seconds.
  bool detection(ssl::SSL_DetectionFrame& out);
  // The next processed frame with its detections, waiting up to timeout_s;
  // when none comes in time, the last one taken before (false: never one).
  // `fresh` says which it is.
  // `setup` (optional): the calibration and pipeline options the processor
  // used on that frame, for the console's own pipeline run (console_layers.h).
  struct Setup {
    bool known = false;  // false: no processor had made the frame
    CameraCalibration calibration;
    PipelineOptions pipeline;
  };
  bool snapshot(double timeout_s, Frame& frame, ssl::SSL_DetectionFrame& detection, bool& fresh,
                Setup* setup = nullptr);
  // The learned class colors and the recent blobs' colors (chromaticity,
  // color_classes.h), newest last; false before any frame was seen since
  // the first ask (asking keeps them coming for the next few seconds).
  struct BlobColor {
    ColorVec color;
    float score = 0;
  };
  struct Colors {
    ColorVec classes[Detector::kClassColorCount];
    Detector::ColorSeparations separations;
    std::vector<BlobColor> blobs;
  };
  bool colors(Colors& out);
  static constexpr size_t kBlobRing = 600;  // blobs kept: ten frames' worth of a full field

 private:
  uint32_t camera_id_;
  std::atomic<int64_t> detections_wanted_until_ms_{0};  // steady clock
  std::atomic<int> snapshot_waiters_{0};
  std::mutex mutex_;
  std::condition_variable taken_;
  bool have_detection_ = false;
  ssl::SSL_DetectionFrame detection_;
  uint64_t snapshots_ = 0;  // frames copied for snapshots
  Frame frame_;             // the newest of them
  ssl::SSL_DetectionFrame frame_detection_;
  Setup frame_setup_;
  std::atomic<int64_t> colors_wanted_until_ms_{0};
  bool have_colors_ = false;
  Colors colors_;          // blobs: a ring of kBlobRing, reserved once
  size_t ring_next_ = 0;   // where the next blob goes once the ring is full
};

}  // namespace dv::app
