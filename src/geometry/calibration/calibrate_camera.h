#pragma once
// One camera's calibration from one image of the field, end to end: line
// pixels, line groups, distortion and principal point, then the pose either
// from user points (four-point mode) or from the lines alone (automatic
// mode), a robust refinement on all line pixels, and the quality gate.
#include <cstdint>
#include <optional>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "geometry/calibration/calibration_quality.h"
#include "geometry/calibration/field_symmetry.h"
#include "geometry/calibration/intrinsics.h"
#include "geometry/calibration/lens_fit.h"
#include "geometry/calibration/line_groups.h"
#include "geometry/calibration/point_pose.h"
#include "geometry/calibration/pose_uncertainty.h"
#include "geometry/calibration/view_hint.h"
#include "geometry/camera_model.h"
#include "geometry/field_model.h"

namespace dv {

struct CalibrationRequest {
  uint32_t camera_id = 0;
  // Cameras on the field in SSL-Vision's layout; 0 picks 4 for a Division A
  // sized field and 2 otherwise.
  unsigned num_cameras = 0;
  // Four or more known field points with their image positions; empty asks
  // for the automatic mode. The points alone place the camera: neither the
  // camera id's region nor the hint is used then.
  std::vector<PointCorrespondence> points;
  // Automatic mode: where the camera looks; without it the camera-id layout
  // settles the field's symmetry (and says so).
  ViewHint hint;
  std::optional<double> camera_height_mm;
  // Automatic mode refuses a pose whose predicted field error is over the
  // bar; a joint refinement over several cameras that judges the seams
  // itself may take such a pose as its start (the prediction is reported).
  bool refuse_unpinned = true;
  std::string source = "image";  // names the image in messages
};

// What the image shows of the field lines, computed once per image.
struct LineObservation {
  cv::Mat mask;                // 255 at line pixels
  cv::Mat distance;            // distance transform to the nearest line pixel
  std::vector<ImagePx> mask_pixels;  // thinned list of line pixels (mask positions)
  std::vector<ImagePx> pixels;       // the same moved to their line's centre (sub-pixel)
  std::vector<LineGroup> groups;
  int half_width_px = 3;
};

// `image`: a Bayer RGGB mosaic (CV_8UC1) or BGR (CV_8UC3); the line width
// in pixels is expected from the camera seeing `region` (plus some overlap)
// or from the field size of a pixel.
LineObservation observeLines(const cv::Mat& image, const FieldModel& field, const FieldRect& region);
LineObservation observeLinesAtScale(const cv::Mat& image, const FieldModel& field, double mm_per_px);

struct CalibrationOutcome {
  CameraCalibration calibration;
  CalibrationMeasures measures;
  // Set when no calibration may be published, with the reason; the caller
  // must not write or send `calibration` then.
  std::optional<std::string> problem;
  std::optional<IntrinsicsResult> intrinsics;
  // Automatic mode: how far off the field positions may be, given what the
  // lines in view pin down.
  std::optional<PredictedFieldError> predicted_error;
  bool refinement_accepted = false;
  // The lens terms beyond the league's model, tried once a pose is found;
  // `calibration` carries them when the lines support them.
  std::optional<LensFitResult> lens;
  bool automatic = false;
  bool has_pose = false;  // `calibration` holds a pose (passed or refused)
  // How the field's half-turn symmetry was settled; empty when no pose was
  // found to decide about.
  std::optional<SymmetryDecision> symmetry;
  // What the image showed (for the report).
  LineObservation lines;
};

// The region of the field camera `id` covers (SSL-Vision layout).
FieldRect cameraRegionFor(const FieldModel& field, uint32_t camera_id, unsigned num_cameras,
                          const std::string& source);

// Throws InputError(request.source, ...) for unusable input (no field
// lines in the image, points outside the image, too few points); quality
// problems are returned in `problem`.
CalibrationOutcome calibrateCamera(const cv::Mat& image, const FieldModel& field,
                                   const CalibrationRequest& request);

}  // namespace dv
