#pragma once
// One camera's processing chain as `run` and `bench` use it: pixel pipeline
// (raw frame -> blobs) then detector (blobs -> robots and balls), with the
// time each part took. Buffers live here and are reused frame after frame.
#include <memory>
#include <string>

#include "detection/detector.h"
#include "geometry/camera_model.h"
#include "geometry/field_model.h"
#include "io/frame_source.h"
#include "pipeline/backend.h"

namespace dv::app {

struct ProcessorOptions {
  PipelineOptions pipeline;
  DetectorOptions detector;
  BackendChoice backend;  // CPU reference unless asked otherwise
};

// The pipeline's Bayer setting for a frame source's pixel format.
BayerPattern bayerPatternOf(PixelFormat format);
// --bayer-sampling auto|subsample|full; InputError naming the option otherwise.
BayerSampling bayerSamplingFromName(const std::string& text);

class CameraProcessor {
 public:
  // Throws InputError (from the pipeline) when the camera sees no field, the
  // calibration has no image size, or an explicitly chosen backend fails.
  CameraProcessor(const CameraCalibration& calibration, const FieldModel& field,
                  const ProcessorOptions& options);

  // Processes one frame. Returns false and sets `why` when the pipeline
  // rejects it (wrong size or pixel format); `out` is then empty.
  bool process(const Frame& frame, Detections& out, std::string& why);

  const CameraModel& camera() const { return camera_; }
  const PixelPipeline& pipeline() const { return *pipeline_; }
  const FieldModel& field() const { return field_; }
  // What makePipeline chose and why ("cpu", "opencl <device>", ...).
  const std::string& backendNote() const { return backend_note_; }
  const BlobList& blobs() const { return blobs_; }
  const Detector& detector() const { return detector_; }
  // From the next frame on; tracks stay. Throws InputError when invalid.
  void setDetectorOptions(const DetectorOptions& o) { detector_.setOptions(o); }
  double lastPipelineMs() const { return pipeline_ms_; }
  double lastDetectionMs() const { return detection_ms_; }

 private:
  CameraModel camera_;
  FieldModel field_;
  std::string backend_note_;
  std::unique_ptr<PixelPipeline> pipeline_;
  Detector detector_;
  BlobList blobs_;
  ExpectedPlaces expected_;
  double pipeline_ms_ = 0;
  double detection_ms_ = 0;
};

}  // namespace dv::app
