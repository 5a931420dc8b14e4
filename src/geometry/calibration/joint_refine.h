#pragma once
// Joint refinement of several cameras on the field lines they see (beyond
// the thesis). Painted lines are never exactly where the field model puts
// them; fitting each camera alone to the model lets two cameras disagree
// where they both see a misplaced line. Here all cameras are refined
// together and every model line gets a small shared offset (along its normal;
// the circle a radius change) with a weak prior, so that the cameras agree on
// the line as painted and their seams match.
#include <vector>

#include "core/units.h"
#include "geometry/calibration/line_fit.h"
#include "geometry/camera_model.h"
#include "geometry/field_model.h"

namespace dv {

struct CameraLines {
  CameraCalibration calibration;
  std::vector<ImagePx> line_pixels;
  bool fix_height = false;
};

struct JointRefineOptions {
  double gate_px = 4;
  double loss_scale_px = 1.0;
  double line_offset_sigma_mm = 15;
  double principal_point_sigma_px = 30;
  int max_pixels_per_camera = 12000;
};

struct JointRefineResult {
  std::vector<CameraCalibration> calibrations;
  std::vector<double> line_offsets_mm;  // per FieldLineModel element
  double cost_before = 0, cost_after = 0;
  bool accepted = false;  // false: the calibrations are the inputs unchanged
};

JointRefineResult refineJointly(const std::vector<CameraLines>& cameras, const FieldModel& field,
                                const JointRefineOptions& options = {});

// Mean offset (mm) between two cameras' estimated field positions of the
// same points at `height`: points on a field grid seen by both true cameras
// are imaged with the truths and placed back on the field with the estimates.
double meanSeamOffset(const CameraCalibration& truth_a, const CameraCalibration& estimate_a,
                      const CameraCalibration& truth_b, const CameraCalibration& estimate_b, double height,
                      double step_mm = 50, int* samples = nullptr);

}  // namespace dv
