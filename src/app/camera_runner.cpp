#include "app/camera_runner.h"


#include <chrono>

#include "core/clock.h"
#include "core/error.h"
#include "detection/detection_frame.h"

namespace dv::app {

namespace {
constexpr size_t kTimesReserved = 1 << 20;  // a summary's worth (4.6 hours at 60 fps)
}  // namespace

CameraRunner::CameraRunner(const CameraCalibration& calibration, const FieldModel& field,
                           const ProcessorOptions& options, std::unique_ptr<CameraSource> source,
                           PacketOutputs& outputs, LogFn log, LiveCameraOptions live)
    : calibration_(calibration),
      field_(field),
      options_(options),
      outputs_(outputs),
      log_(log),
      camera_("camera " + std::to_string(calibration.camera_id), std::move(source),
              [this](Frame& f, double t) { onFrame(f, t); }, log, live) {
  times_.total_ms.reserve(kTimesReserved);
  times_.pipeline_ms.reserve(kTimesReserved);
  times_.detection_ms.reserve(kTimesReserved);
  heights_[0] = options.detector.robot_height_yellow;
  heights_[1] = options.detector.robot_height_blue;
  scratch_.reserve(8192);
}

CameraRunner::~CameraRunner() { stop(); }

void CameraRunner::start() {
  last_status_t_ = unixSeconds();
  camera_.start();
}
void CameraRunner::stop() { camera_.stop(); }

void CameraRunner::setDetectorOptions(const DetectorOptions& o) {
  std::lock_guard<std::mutex> lock(mutex_);
  pending_options_ = o;
}

void CameraRunner::setCalibration(const CameraCalibration& c) {
  std::lock_guard<std::mutex> lock(mutex_);
  pending_calibration_ = c;
}

void CameraRunner::onFrame(Frame& frame, double t_taken) {
  if (failed_) return;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (pending_calibration_) {
      if (processor_) previous_calibration_ = calibration_;
      calibration_ = *pending_calibration_;
      pending_calibration_.reset();
      processor_.reset();   // rebuilt below with the new calibration
      warmed_up_ = false;   // that rebuild is a start-up cost, not a latency
      refusal_logged_ = false;  // a new calibration may refuse what the old one took
    }
    if (pending_options_) {
      options_.detector = *pending_options_;
      pending_options_.reset();
      if (processor_) {
        try {
          processor_->setDetectorOptions(options_.detector);
        } catch (const InputError& e) {
          log_("camera " + std::to_string(calibration_.camera_id) + ": new detector options refused: " + e.what());
        }
      }
      heights_[0] = processor_ ? processor_->detector().options().robot_height_yellow : options_.detector.robot_height_yellow;
      heights_[1] = processor_ ? processor_->detector().options().robot_height_blue : options_.detector.robot_height_blue;
    }
  }
  if (!processor_) {
    CameraCalibration c = calibration_;
    if (c.image_width == 0 || c.image_height == 0) {
      c.image_width = static_cast<uint32_t>(frame.image.cols);
      c.image_height = static_cast<uint32_t>(frame.image.rows);
    }
    ProcessorOptions o = options_;
    o.pipeline.bayer = bayerPatternOf(frame.format);
    try {
      processor_.emplace(c, field_, o);
    } catch (const std::exception& e) {
      if (previous_calibration_) {  // a new calibration it cannot work with: keep the one that worked
        log_("camera " + std::to_string(calibration_.camera_id) + ": the new calibration is refused: " + e.what());
        calibration_ = *previous_calibration_;
        previous_calibration_.reset();
        return;  // rebuilt with the old one at the next frame
      }
      {
        std::lock_guard<std::mutex> lock(mutex_);
        failure_ = e.what();
      }
      failed_ = true;
      log_("camera " + std::to_string(calibration_.camera_id) + ": cannot process its frames: " + failure_);
      return;
    }
    log_("camera " + std::to_string(calibration_.camera_id) + ": " + processor_->pipeline().samplingNote());
    previous_calibration_.reset();
    std::lock_guard<std::mutex> lock(mutex_);
    backend_ = processor_->pipeline().name();
  }
  std::string why;
  if (!processor_->process(frame, detections_, why)) {
    // Wrong size or format: counted; the first of a run, and the first
    // under each new calibration, is reported.
    {
      std::lock_guard<std::mutex> lock(mutex_);
      if (++rejected_frames_ == 1) rejected_why_ = frame.name + ": " + why;
    }
    if (!refusal_logged_)
      log_("camera " + std::to_string(calibration_.camera_id) + ": skipped " + frame.name + ": " + why +
           " (every such frame is skipped and counted)");
    refusal_logged_ = true;
    return;
  }
  FrameStamp stamp;
  stamp.camera_id = calibration_.camera_id;
  stamp.frame_number = frame.index;
  stamp.t_capture = frame.t_capture;
  stamp.t_capture_camera = frame.t_capture_camera;
  stamp.t_sent = unixSeconds();
  fillDetectionPacket(detections_, stamp, packet_);
  outputs_.detection(packet_);
  // Strings only when a color state changes (color_health.h).
  const unsigned color_changes = colors_.update(processor_->detector().health());
  if (color_changes || colors_.castChanged())
    colors_.sayChanges(color_changes, [&](bool warning, const std::string& text) {
      log_("camera " + std::to_string(calibration_.camera_id) + (warning ? ": warning: " : ": ") + text);
    });
  if (color_changes) {
    std::string issues;
    for (int i = 0; i < kColorIssueCount; ++i)
      if (colors_.active(static_cast<ColorIssue>(i)))
        issues += (issues.empty() ? "" : "; ") + std::string(ColorHealthWatch::name(static_cast<ColorIssue>(i)));
    std::lock_guard<std::mutex> lock(mutex_);
    color_issues_ = issues;
  }
  const double arrival = frame.t_arrival > 0 ? frame.t_arrival : t_taken;
  const double t_done = unixSeconds();
  for (const FrameHook& hook : hooks_) hook(frame, packet_);

  std::lock_guard<std::mutex> lock(mutex_);
  // The first frame built the processor: a start-up cost, not a latency.
  if (!warmed_up_) {
    warmed_up_ = true;
    return;
  }
  const double total_ms = (t_done - arrival) * 1e3;
  wait_.add(t_done, (t_taken - arrival) * 1e3);
  pipeline_.add(t_done, processor_->lastPipelineMs());
  detection_.add(t_done, processor_->lastDetectionMs());
  total_.add(t_done, total_ms);
  if (times_.total_ms.size() < kTimesReserved) {
    times_.total_ms.push_back(total_ms);
    times_.pipeline_ms.push_back(processor_->lastPipelineMs());
    times_.detection_ms.push_back(processor_->lastDetectionMs());
  }
  ++second_.frames;
  second_.blobs += processor_->blobs().blobs.size();
  second_.robots += detections_.robots.size();
  second_.balls += detections_.balls.size();
  for (const auto& r : detections_.robots) (r.team == Team::Yellow ? second_.yellow : second_.blue) += 1;
  separations_ = processor_->detector().colorSeparations();
  lines_ = processor_->detector().health().lines;
}

CameraRunner::Times CameraRunner::times() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return times_;
}

CameraStatus CameraRunner::status() {
  CameraStatus s;
  s.camera_id = calibration_.camera_id;
  s.source = camera_.source().describe();
  s.counters = camera_.counters();
  s.t_unix = unixSeconds();
  {
    std::lock_guard<std::mutex> lock(mutex_);
    s.backend = backend_;
    const double dt = std::max(1e-3, s.t_unix - last_status_t_);
    s.fps_in = (s.counters.frames_in - last_in_) / dt;
    s.fps_out = (s.counters.processed - last_processed_) / dt;
    last_in_ = s.counters.frames_in;
    last_processed_ = s.counters.processed;
    last_status_t_ = s.t_unix;
    auto fig = [&](const LatencyWindow& w) {
      return LatencyFigure{w.percentile(s.t_unix, 0.5, scratch_), w.percentile(s.t_unix, 0.99, scratch_)};
    };
    s.wait = fig(wait_);
    s.pipeline = fig(pipeline_);
    s.detection = fig(detection_);
    s.total = fig(total_);
    const double per = second_.frames ? 1.0 / second_.frames : 0;
    s.blobs_per_frame = second_.blobs * per;
    s.robots_per_frame = second_.robots * per;
    s.balls_per_frame = second_.balls * per;
    s.yellow_per_frame = second_.yellow * per;
    s.blue_per_frame = second_.blue * per;
    second_ = {};
    s.separation_yellow_blue = separations_.yellow_blue;
    s.separation_green_pink = separations_.green_pink;
    s.separation_orange_field = separations_.orange_field;
    s.robot_height_yellow = heights_[0];
    s.robot_height_blue = heights_[1];
    s.color_issues = color_issues_;
    s.lines_valid = lines_.valid;
    for (int k = 0; k < 3; ++k) s.lines_rgb[k] = lines_.rgb[k];
  }
  {
    std::lock_guard<std::mutex> lock(mutex_);
    s.counters.skipped += rejected_frames_;  // frames the pipeline refused (wrong size or format)
    s.counters.processed -= std::min(s.counters.processed, rejected_frames_);
    if (rejected_frames_ > 0 && s.counters.last_problem.empty()) s.counters.last_problem = rejected_why_;
  }
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (!failure_.empty()) {  // the processor could not be built: every frame is refused
      s.counters.last_problem = failure_;
      s.counters.skipped += s.counters.processed;
      s.counters.processed = 0;
    }
  }
  s.health_changed = health_.update(s);
  if (s.health_changed)
    log_("camera " + std::to_string(s.camera_id) + ": health " + healthName(s.health) +
         (s.health_reason.empty() ? "" : ": " + s.health_reason));
  return s;
}

}  // namespace dv::app
