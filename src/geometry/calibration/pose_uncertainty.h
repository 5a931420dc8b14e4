#pragma once
// How well the line pixels in view pin a calibration down: the covariance
// of the camera parameters from the line fit's Jacobian at the solution
// (the pixel noise taken from the residuals' spread), carried over to the
// field positions of image pixels at the carpet and at robot height. A view
// with too little of the field in it (a centre circle and two lines, a
// straight-down view without its height) has a large predicted error even
// when the lines fit perfectly; such a pose must not be written.
#include <optional>
#include <vector>

#include "core/units.h"
#include "geometry/calibration/camera_params.h"
#include "geometry/calibration/field_line_model.h"
#include "geometry/field_model.h"

namespace dv {

struct PredictedFieldError {
  double at_carpet_mm = 0;  // mean over image pixels on `area`, 1 sigma, z = 0
  double at_150_mm = 0;     // the same at z = 150 mm
  int pixels_used = 0;
  double noise_px = 0;      // residual spread the prediction assumes
};

struct PoseUncertaintyOptions {
  bool height_fixed = false;
  // A prior on the principal point, px (1 sigma); none by default: the
  // line fit's prior keeps it from wandering but is no measurement.
  double principal_point_sigma_px = 0;
  int max_pixels = 4000;
  int width = 0, height = 0;
};

// Empty when too few line pixels match to say anything.
std::optional<PredictedFieldError> predictFieldError(const CameraParams& params,
                                                     const std::vector<ImagePx>& line_pixels,
                                                     const FieldLineModel& model, const FieldRect& area,
                                                     const PoseUncertaintyOptions& options);

}  // namespace dv
