#pragma once
// One live camera of `run` or `serve`: a LiveCamera (capture and processing
// threads) whose processing function runs the CameraProcessor and hands the
// packet to the shared outputs, plus the figures of its status record.
// The processor is built on the first frame (whose size and pixel format it
// then expects); a camera whose processor cannot be built says why and
// stops alone. Detector options (robot heights from the game controller, a
// reloaded config) are handed over between frames, keeping the tracks.
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "app/camera_processor.h"
#include "app/packet_outputs.h"
#include "detection/color_health.h"
#include "live/camera_status.h"
#include "live/health_monitor.h"
#include "live/latency_window.h"
#include "live/live_camera.h"

namespace dv::app {

class CameraRunner {
 public:
  using LogFn = std::function<void(const std::string&)>;
  // A hook on the processing thread after each frame's packet went out.
  using FrameHook = std::function<void(const Frame&, const ssl::SSL_WrapperPacket&)>;

  CameraRunner(const CameraCalibration& calibration, const FieldModel& field, const ProcessorOptions& options,
               std::unique_ptr<CameraSource> source, PacketOutputs& outputs, LogFn log,
               LiveCameraOptions live = {});
  ~CameraRunner();

  void start();
  void stop();
  bool ended() const { return camera_.ended(); }
  uint64_t processed() const { return camera_.counters().processed; }
  // Builds the status record now (once a second, from the status thread).
  CameraStatus status();
  // Applied before the next frame; invalid options are logged and ignored.
  void setDetectorOptions(const DetectorOptions& o);
  // A new calibration (accepted on the console): the processor is rebuilt
  // with it before the next frame (the tracks start over).
  void setCalibration(const CameraCalibration& c);
  // Hooks run in the order added; add them before start().
  void addFrameHook(FrameHook hook) { hooks_.push_back(std::move(hook)); }
  uint32_t cameraId() const { return calibration_.camera_id; }
  // The processor of the frame just done: only for frame hooks, which run on
  // the processing thread (null before the first frame).
  const CameraProcessor* processorInHook() const { return processor_ ? &*processor_ : nullptr; }
  CameraSource& source() { return camera_.source(); }
  // Every frame's total latency (arrival -> sent, ms) and stage times, for
  // the summary; reserved up front, so recording them does not allocate.
  struct Times {
    std::vector<double> total_ms, pipeline_ms, detection_ms;
  };
  Times times() const;
  std::string failure() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return failure_;
  }

 private:
  void onFrame(Frame& frame, double t_taken);

  CameraCalibration calibration_;
  FieldModel field_;
  ProcessorOptions options_;
  PacketOutputs& outputs_;
  LogFn log_;
  std::vector<FrameHook> hooks_;  // the raw ring, the console's feed
  std::optional<CameraProcessor> processor_;
  std::string failure_;  // the processor could not be built: why (guarded by mutex_)
  bool failed_ = false;  // the same, for the processing thread alone
  Detections detections_;
  ssl::SSL_WrapperPacket packet_;
  bool warmed_up_ = false;
  uint64_t rejected_frames_ = 0;  // guarded by mutex_ (status() reads it)
  std::string rejected_why_;      // the first refusal, for the status
  bool refusal_logged_ = false;   // processing thread only

  mutable std::mutex mutex_;  // guards what status() reads
  std::optional<DetectorOptions> pending_options_;
  std::optional<CameraCalibration> pending_calibration_;
  std::optional<CameraCalibration> previous_calibration_;  // processing thread only
  LatencyWindow wait_, pipeline_, detection_, total_;
  Times times_;
  struct PerSecond {  // sums since the last status()
    uint64_t frames = 0, blobs = 0, robots = 0, balls = 0, yellow = 0, blue = 0;
  } second_;
  Detector::ColorSeparations separations_;
  std::string backend_;
  double heights_[2] = {0, 0};
  uint64_t last_in_ = 0, last_processed_ = 0;
  double last_status_t_ = 0;
  HealthMonitor health_;
  ColorHealthWatch colors_;  // processing thread only
  std::string color_issues_;  // under mutex_: the color warnings in force
  NeutralColor lines_;        // under mutex_: the lines' last color
  std::vector<double> scratch_;

  LiveCamera camera_;  // last: its threads use the members above
};

}  // namespace dv::app
