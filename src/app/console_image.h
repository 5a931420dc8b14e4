#pragma once
// The console's camera image: a frame demosaiced, scaled down and with the
// layers asked for drawn over it, then encoded. Runs on the console's HTTP
// threads only (never on a detection thread).
#include <optional>
#include <string>
#include <vector>

#include "dotvision/ssl_detection.pb.h"
#include "geometry/camera_model.h"
#include "geometry/field_model.h"
#include "io/frame_source.h"

namespace dv::app {

// raw: the camera image; lines: the field lines projected through the
// calibration in use (a wrong calibration shows at a glance); detections:
// robots (team, id, heading) and balls as the processor found them.
struct SnapshotLayers {
  bool lines = false, detections = false;
};
// "raw", "lines", "detections", or several joined by ',' (raw is always the
// base). Nullopt with `why` for an unknown name.
std::optional<SnapshotLayers> parseSnapshotLayers(const std::string& text, std::string& why);

// The frame at most max_width pixels wide (aspect kept, never enlarged),
// with the layers drawn. `calibration` may be null (then no lines).
cv::Mat renderSnapshot(const Frame& frame, const ssl::SSL_DetectionFrame& detection,
                       const CameraCalibration* calibration, const FieldModel& field, const SnapshotLayers& layers,
                       int max_width);

// The outline on the field (z = 0) of what a camera sees: points along its
// image border that reach the field, in order. Empty when the image size is
// unknown.
std::vector<FieldMm> cameraFootprint(const CameraCalibration& calibration);

}  // namespace dv::app
