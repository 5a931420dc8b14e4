#pragma once
// Inspection views of one frame (--debug-dir/--debug-frame): what the camera
// delivered, what the pipeline made of it, and what was detected.
#include <string>

#include "app/camera_processor.h"
#include "detection/detector.h"
#include "io/frame_source.h"

namespace dv::app {

// Writes into `dir` (created if missing), each named
// cam<C>_frame<K>_<view>.png: raw (demosaiced if Bayer), rectified (color on
// the field grid), gradient (gradient dot product), score (blob score),
// blobs (rectified view with the blobs marked) and detections (robots with
// team, id and heading, balls, drawn over the raw image). Returns the paths
// written. Throws InputError(dir, ...) when a file cannot be written.
std::vector<std::string> writeDebugViews(const std::string& dir, uint32_t camera_id,
                                         const Frame& frame, const CameraProcessor& processor,
                                         const Detections& detections);

// The frame as 8-bit BGR (demosaiced when it is a Bayer mosaic).
cv::Mat frameToBgr(const Frame& frame);

}  // namespace dv::app
