#pragma once
// Refinement of a whole calibration on the line pixels: every line pixel near
// the model is projected onto the field and its distance to the nearest model
// line is minimised (in pixels, scaled by the local mm per pixel), with a
// robust loss and gates that shrink from coarse to fine. Unlike the thesis's
// refinement (squared distance to the nearest line pixel, no outlier
// handling) it cannot be pulled by clutter, and a result that fits worse than
// its start is rejected.
#include <optional>
#include <vector>

#include "core/units.h"
#include "geometry/calibration/camera_params.h"
#include "geometry/calibration/field_line_model.h"
#include "geometry/calibration/point_pose.h"

namespace dv {

struct LineFitOptions {
  std::vector<double> gates_px = {16, 8, 4, 3};
  double loss_scale_px = 1.0;       // Cauchy loss scale
  bool fix_height = false;          // the camera height is given
  bool fit_principal_point = true;
  bool fit_distortion = true;
  // Weak priors (1 sigma) on the principal point and on kappa * half_diag^2
  // around their start, where lines observe them weakly.
  double principal_point_sigma_px = 30;
  double point_sigma_px = 2;        // user points, when given
  int max_pixels = 20000;
  int image_width = 0, image_height = 0;
};

struct LineFitResult {
  CameraParams params;
  double cost_before = 0;  // mean robust cost per matched pixel at the start
  double cost_after = 0;
  int pixels_used = 0;
  bool improved = false;   // false: params are the start values
};

LineFitResult refineOnLines(const CameraParams& start, const std::vector<ImagePx>& line_pixels,
                            const FieldLineModel& model,
                            const std::vector<PointCorrespondence>& points,
                            const LineFitOptions& options);

struct LinePixelMatch {
  ImagePx px;
  int element;        // index into FieldLineModel::elements()
  double mm_per_px;   // local scale on the field at this pixel
  double distance_px;
};
// Line pixels within `gate_px` of the model, with their nearest element and
// the local scale, for the given parameters.
std::vector<LinePixelMatch> matchLinePixels(const CameraParams& p, const std::vector<ImagePx>& pixels,
                                            const FieldLineModel& model, double gate_px);

// Robust mean distance (px) of the line pixels within `gate_px` of the model;
// the score refinements must not make worse. Also returns how many matched.
double robustLineCost(const CameraParams& p, const std::vector<ImagePx>& line_pixels,
                      const FieldLineModel& model, double gate_px, double loss_scale_px,
                      int* matched = nullptr);

}  // namespace dv
