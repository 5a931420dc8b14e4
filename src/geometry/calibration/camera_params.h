#pragma once
// The camera as Ceres sees it: intrinsics (f, cx, cy, k), the field->camera
// rotation as an angle-axis vector and the camera center in field mm. The
// templated helpers are the league's camera model written once for doubles
// and for Ceres' jets.
#include <ceres/rotation.h>

#include <cmath>
#include <cstdint>

#include "core/units.h"
#include "geometry/camera_model.h"

namespace dv {

struct CameraParams {
  double intrinsics[4] = {1000, 0, 0, 0};  // f, cx, cy, k (normalised)
  double rotation[3] = {0, 0, 0};          // angle-axis, field -> camera
  double position[3] = {0, 0, 4000};       // camera center, field mm
  double lens[4] = {0, 0, 0, 0};           // LensTerms k2, k3, p1, p2 (zero: league model)

  static CameraParams fromCalibration(const CameraCalibration& c);
  CameraCalibration toCalibration(uint32_t camera_id, uint32_t width, uint32_t height) const;
};

// Pixel -> point on the plane z = height. False at or above the horizon.
template <typename T>
bool backProjectPixel(const T* intr, const T* rot, const T* pos, double u, double v, double height,
                      T* xy) {
  const T nx = (T(u) - intr[1]) / intr[0];
  const T ny = (T(v) - intr[2]) / intr[0];
  const T s = T(1) + intr[3] * (nx * nx + ny * ny);
  const T ray_cam[3] = {nx * s, ny * s, T(1)};
  const T inverse[3] = {-rot[0], -rot[1], -rot[2]};
  T ray[3];
  ceres::AngleAxisRotatePoint(inverse, ray_cam, ray);
  if (!(ray[2] < T(-1e-9))) return false;
  const T t = (T(height) - pos[2]) / ray[2];
  xy[0] = pos[0] + t * ray[0];
  xy[1] = pos[1] + t * ray[1];
  return true;
}

// The same through a lens with terms beyond the league's (LensTerms order).
template <typename T>
bool backProjectPixelLens(const T* intr, const T* lens, const T* rot, const T* pos, double u, double v,
                          double height, T* xy) {
  const T dx = (T(u) - intr[1]) / intr[0];
  const T dy = (T(v) - intr[2]) / intr[0];
  T ray_cam[3] = {T(0), T(0), T(1)};
  if (!(undistortNormalised(dx, dy, intr[3], lens, &ray_cam[0], &ray_cam[1]) > T(0))) return false;
  const T inverse[3] = {-rot[0], -rot[1], -rot[2]};
  T ray[3];
  ceres::AngleAxisRotatePoint(inverse, ray_cam, ray);
  if (!(ray[2] < T(-1e-9))) return false;
  const T t = (T(height) - pos[2]) / ray[2];
  xy[0] = pos[0] + t * ray[0];
  xy[1] = pos[1] + t * ray[1];
  return true;
}

// Reprojection error in (undistorted) pixels of a field point against an
// image pixel: the pixel is undistorted (closed form in this model) and
// compared with the pinhole projection of the point. False behind the camera.
template <typename T>
bool pointReprojection(const T* intr, const T* rot, const T* pos, const FieldPoint& p,
                       const ImagePx& px, T* residual) {
  const T rel[3] = {T(p.x) - pos[0], T(p.y) - pos[1], T(p.z) - pos[2]};
  T pc[3];
  ceres::AngleAxisRotatePoint(rot, rel, pc);
  if (!(pc[2] > T(1e-6))) {
    // Behind the camera: a flat, large residual, so that the solver turns
    // away instead of failing (a failed first evaluation stops Ceres).
    residual[0] = residual[1] = T(1e4);
    return true;
  }
  const T nx = (T(px.u) - intr[1]) / intr[0];
  const T ny = (T(px.v) - intr[2]) / intr[0];
  const T s = T(1) + intr[3] * (nx * nx + ny * ny);
  residual[0] = intr[0] * (nx * s - pc[0] / pc[2]);
  residual[1] = intr[0] * (ny * s - pc[1] / pc[2]);
  return true;
}

// Keeps the principal point near a prior (cx, cy) with spread sigma px; the
// line fits cannot see it well on their own.
struct PrincipalPointPrior {
  PrincipalPointPrior(double cx, double cy, double sigma) : cx(cx), cy(cy), sigma(sigma) {}
  template <typename T>
  bool operator()(const T* intr, T* r) const {
    r[0] = (intr[1] - T(cx)) / T(sigma);
    r[1] = (intr[2] - T(cy)) / T(sigma);
    return true;
  }
  double cx, cy, sigma;
};

// Cauchy cost of a residual d at scale s (the robust loss used to compare fits).
inline double cauchyCost(double d, double s) { return s * s * std::log1p(d * d / (s * s)); }

// Whether a field point lies in front of the camera.
inline bool inFrontOfCamera(const double* rot, const double* pos, const FieldPoint& p) {
  const double rel[3] = {p.x - pos[0], p.y - pos[1], p.z - pos[2]};
  double pc[3];
  ceres::AngleAxisRotatePoint(rot, rel, pc);
  return pc[2] > 1e-6;
}

}  // namespace dv
