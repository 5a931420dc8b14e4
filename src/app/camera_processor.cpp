#include "app/camera_processor.h"

#include <chrono>

#include "core/error.h"

namespace dv::app {

namespace {
using Clock = std::chrono::steady_clock;
double msBetween(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration<double, std::milli>(b - a).count();
}
}  // namespace

BayerPattern bayerPatternOf(PixelFormat format) {
  switch (format) {
    case PixelFormat::Bgr8: return BayerPattern::None;
    case PixelFormat::BayerRggb8: return BayerPattern::RGGB;
    case PixelFormat::BayerGrbg8: return BayerPattern::GRBG;
    case PixelFormat::BayerGbrg8: return BayerPattern::GBRG;
    case PixelFormat::BayerBggr8: return BayerPattern::BGGR;
  }
  return BayerPattern::RGGB;
}

BayerSampling bayerSamplingFromName(const std::string& text) {
  BayerSampling s = BayerSampling::Auto;
  if (!parseBayerSampling(text.c_str(), s))
    throw InputError("command line", "unknown --bayer-sampling '" + text + "' (expected auto, subsample or full)");
  return s;
}

CameraProcessor::CameraProcessor(const CameraCalibration& calibration, const FieldModel& field,
                                 const ProcessorOptions& options)
    : camera_(calibration),
      field_(field),
      pipeline_(makePipeline(camera_, field, options.pipeline, options.backend, &backend_note_)),
      detector_(camera_, field, options.detector) {}

bool CameraProcessor::process(const Frame& frame, Detections& out, std::string& why) {
  const auto t0 = Clock::now();
  const bool ok = pipeline_->process(frame.image, blobs_);
  const auto t1 = Clock::now();
  pipeline_ms_ = msBetween(t0, t1);
  if (!ok) {
    why = pipeline_->lastError();
    pipeline_->expect({});
    out.balls.clear();
    out.robots.clear();
    detection_ms_ = 0;
    return false;
  }
  detector_.process(blobs_, frame.t_capture, out, FrameView{&frame.image, pipeline_->options().bayer});
  // Where a fast ball will be: the next frame keeps weak peaks there.
  detector_.expectedBalls(expected_);
  pipeline_->expect(expected_);
  detection_ms_ = msBetween(t1, Clock::now());
  return true;
}

}  // namespace dv::app
