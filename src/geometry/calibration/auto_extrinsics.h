#pragma once
// Extrinsics without clicked points (beyond the thesis): hypotheses from
// matching pairs of detected straight lines to pairs of model lines anywhere
// on the field, and from the centre circle's ellipse with the halfway line,
// scored on the line pixels, the best refined on all line pixels coarse to
// fine. The pose is found up to the field's half turn, which the caller
// settles; when two poses that are not each other's twins fit about equally
// well the result is "cannot decide".
#include <optional>
#include <string>

#include "geometry/calibration/calibrate_camera.h"
#include "geometry/calibration/camera_params.h"

namespace dv {

struct AutoExtrinsicsOptions {
  std::optional<double> camera_height_mm;
  int max_refined_hypotheses = 6;
  int reranked_hypotheses = 80;
};

struct AutoExtrinsicsResult {
  // Every pose that fits the lines about equally well, each up to its half
  // turn, the best first; one in the usual case, more where the view itself
  // is symmetric (the centre circle with both centre lines and nothing else
  // looks the same after a quarter turn). The caller picks with outside
  // knowledge or refuses.
  std::vector<CameraParams> readings;
  std::string reason;  // why readings is empty
  int hypotheses = 0;
};

AutoExtrinsicsResult findPoseAutomatically(const LineObservation& obs, const PixelDistortion& distortion,
                                           const FieldModel& field, int width, int height,
                                           const AutoExtrinsicsOptions& options);

}  // namespace dv
