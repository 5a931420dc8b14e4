#pragma once
// The league's one-coefficient model that best stands in for a calibration
// with lens terms (LensTerms): what SSL geometry packets carry, since teams
// read only the league's fields. The fit minimises the field distance, at
// z = 0 and z = 150 mm, between where the two models put the same pixel, over
// a grid covering the image; all parameters (focal length, principal point,
// k, rotation, position) are free.
#include "geometry/camera_model.h"

namespace dv {

// Field distance (mm) between two models' back-projections of the same
// pixels, over a grid on the image of `a` at z = 0 and z = 150 mm.
struct ModelDifference {
  double mean_mm = 0;
  double max_mm = 0;
  int samples = 0;
};
ModelDifference modelDifference(const CameraCalibration& a, const CameraCalibration& b);

struct LeagueFit {
  CameraCalibration calibration;  // lens terms zero
  ModelDifference residual;       // against the calibration it stands in for
};

// `c` itself (residual zero) when it has no lens terms.
LeagueFit leagueFit(const CameraCalibration& c);

}  // namespace dv
