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
#include "pipeline/blob.h"
#include "pipeline/rectified_grid.h"

namespace dv::app {

// One picture is the base: raw (the camera image) or, from the console's own
// pipeline run on the frame (console_layers.h), a picture on the rectified
// field grid: rectified (the colors on the grid), chroma (those colors
// divided by their brightness), gradient (the color gradient dot product)
// or score (the blob score; both gray, 128 = 0). Drawn over it: lines (the
// field lines projected through the calibration in use, so a wrong one
// shows at a glance), detections (robots with team, id and heading, and
// balls, as the processor found them) and blobs (the pixel stage's blobs,
// filled with their color, and its weak peaks, rings).
enum class SnapshotBase { Raw, Rectified, Chroma, Gradient, Score };
struct SnapshotLayers {
  SnapshotBase base = SnapshotBase::Raw;
  bool lines = false, detections = false, blobs = false;
  bool onGrid() const { return base != SnapshotBase::Raw; }
  bool needsPipeline() const { return onGrid() || blobs; }
};
// Layer names joined by ',' (at most one base; raw when none). Nullopt with
// `why` for an unknown name or two bases.
std::optional<SnapshotLayers> parseSnapshotLayers(const std::string& text, std::string& why);

// What a snapshot is drawn from.
struct SnapshotSource {
  Frame frame;
  ssl::SSL_DetectionFrame detection;
  std::optional<CameraCalibration> calibration;  // none: no lines
  // From the console's pipeline run on `frame` (grid layers and blobs only):
  std::optional<RectifiedGrid> grid;
  double plane_height = 0;  // mm, the plane the grid lies on
  BlobList blobs;
  cv::Mat grid_picture;  // grid sized, the base asked for: BGR or gray
};

// The base at most max_width pixels wide (aspect kept, never enlarged),
// with the layers drawn.
cv::Mat renderSnapshot(const SnapshotSource& source, const FieldModel& field, const SnapshotLayers& layers,
                       int max_width);

// The outline on the field (z = 0) of what a camera sees: points along its
// image border that reach the field, in order. Empty when the image size is
// unknown.
std::vector<FieldMm> cameraFootprint(const CameraCalibration& calibration);

}  // namespace dv::app
