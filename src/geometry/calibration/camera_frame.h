#pragma once
// A field point in the camera's frame for Ceres residuals over a pose kept
// as an angle-axis rotation and the camera's position (both point-pose fits
// use it).
#include <ceres/rotation.h>

#include "core/units.h"

namespace dv {

// pc = R(rot) (p - pos). False when the point is not in front of the
// camera: the caller then gives a flat, large residual, so that the solver
// turns away.
template <typename T>
bool pointInCameraFrame(const FieldPoint& p, const T* rot, const T* pos, T pc[3]) {
  const T rel[3] = {T(p.x) - pos[0], T(p.y) - pos[1], T(p.z) - pos[2]};
  ceres::AngleAxisRotatePoint(rot, rel, pc);
  return pc[2] > T(1e-6);
}

}  // namespace dv
