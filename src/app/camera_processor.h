#pragma once
// One camera's processing chain as `run` and `bench` use it: pixel pipeline
// (raw frame -> blobs) then detector (blobs -> robots and balls), with the
// time each part took. Buffers live here and are reused frame after frame.
#include <string>

#include "detection/detector.h"
#include "geometry/camera_model.h"
#include "geometry/field_model.h"
#include "io/frame_source.h"
#include "pipeline/cpu_pipeline.h"

namespace dv::app {

struct ProcessorOptions {
  PipelineOptions pipeline;
  DetectorOptions detector;
};

// The pipeline's Bayer setting for a frame source's pixel format.
BayerPattern bayerPatternOf(PixelFormat format);

class CameraProcessor {
 public:
  // Throws InputError (from the pipeline) when the camera sees no field or
  // the calibration has no image size.
  CameraProcessor(const CameraCalibration& calibration, const FieldModel& field,
                  const ProcessorOptions& options);

  // Processes one frame. Returns false and sets `why` when the pipeline
  // rejects it (wrong size or pixel format); `out` is then empty.
  bool process(const Frame& frame, Detections& out, std::string& why);

  const CameraModel& camera() const { return camera_; }
  const CpuPipeline& pipeline() const { return pipeline_; }
  const BlobList& blobs() const { return blobs_; }
  double lastPipelineMs() const { return pipeline_ms_; }
  double lastDetectionMs() const { return detection_ms_; }

 private:
  CameraModel camera_;
  CpuPipeline pipeline_;
  Detector detector_;
  BlobList blobs_;
  double pipeline_ms_ = 0;
  double detection_ms_ = 0;
};

}  // namespace dv::app
