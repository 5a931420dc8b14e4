#pragma once
// The league's camera model (SSL_GeometryCameraCalibration): a pinhole with
// one radial distortion coefficient, a field->camera rotation quaternion and a
// translation in camera coordinates. Operations follow SSL-Vision's order,
// including its quaternion normalisation rule, so results agree with it where
// it is right. Where it is not, dotvision differs on purpose:
//  - field->image inverts the distortion for either sign of k (SSL-Vision
//    ignores k <= 0 there, so its two directions are not inverses);
//  - the principal point and the optical axis map to each other instead of NaN;
//  - rays at or above the horizon are reported as such instead of giving
//    points behind the camera.
// Beyond the league's model a calibration may carry Brown-Conrady terms
// (LensTerms) for real wide-angle lenses; all zero is the league's model,
// number for number.
#include <Eigen/Core>
#include <cstdint>
#include <optional>

#include "core/units.h"

namespace dv {

// Lens terms beyond the league's single radial coefficient: the polynomial
// of Brown-Conrady (OpenCV's k1..k3, p1, p2), but in the league's direction,
// from distorted to undistorted normalised coordinates. With d = (x, y) the
// distorted point ((pixel - principal point) / focal) and r^2 = x^2 + y^2:
//   u = d (1 + k1 r^2 + k2 r^4 + k3 r^6)
//       + (2 p1 x y + p2 (r^2 + 2 x^2),  p1 (r^2 + 2 y^2) + 2 p2 x y)
// where k1 is the league's `distortion`. OpenCV's coefficients map the other
// way (undistorted to distorted), so the same lens has other numbers there
// (k1 about -k1 here); convert by fitting, not by copying.
// These terms are not part of SSL_GeometryCameraCalibration: geometry files
// keep them in dotvision's own keys, and packets carry the best fit of the
// league's model (leagueFit).
struct LensTerms {
  double k2 = 0, k3 = 0;  // r^4, r^6
  double p1 = 0, p2 = 0;  // tangential
  bool any() const { return k2 != 0 || k3 != 0 || p1 != 0 || p2 != 0; }
  bool operator==(const LensTerms&) const = default;
};

// The mapping above, written once for doubles and Ceres' jets. Returns the
// radial factor (1 + k1 r^2 + ...), which must be positive for a real ray.
template <typename T>
T undistortNormalised(const T& x, const T& y, const T& k1, const T* lens, T* ux, T* uy) {
  const T r2 = x * x + y * y;
  const T s = T(1) + r2 * (k1 + r2 * (lens[0] + r2 * lens[1]));
  *ux = x * s + T(2) * lens[2] * x * y + lens[3] * (r2 + T(2) * x * x);
  *uy = y * s + lens[2] * (r2 + T(2) * y * y) + T(2) * lens[3] * x * y;
  return s;
}

struct CameraCalibration {
  uint32_t camera_id = 0;
  double focal_length = 1000;  // px
  double principal_point_x = 0;  // px
  double principal_point_y = 0;  // px
  double distortion = 0;  // k in r_u = r_d (1 + k r_d^2), normalised units
  double q0 = 1, q1 = 0, q2 = 0, q3 = 0;  // field->camera rotation, q3 scalar
  double tx = 0, ty = 0, tz = 4000;  // mm, camera frame
  uint32_t image_width = 0;  // px, 0 = unknown
  uint32_t image_height = 0;
  LensTerms lens;  // zero: the league's model; not sent in SSL packets

  bool operator==(const CameraCalibration&) const = default;

  // Calibration of a camera at `position` (field mm) whose rotation is R
  // (field -> camera), with t = -R C.
  static CameraCalibration fromPose(uint32_t id, double focal, double cx, double cy, double k,
                                    const Eigen::Matrix3d& field_to_camera,
                                    const Eigen::Vector3d& position);
};

class CameraModel {
 public:
  explicit CameraModel(const CameraCalibration& c);

  const CameraCalibration& calibration() const { return calib_; }

  // Field point -> image pixel. Empty for points behind the camera or beyond
  // the radius the distortion model can reach (k < 0).
  std::optional<ImagePx> fieldToImage(const FieldPoint& p) const;

  // Image pixel -> point on the horizontal plane z = height. Empty where the
  // pixel's ray does not meet that plane in front of the camera (horizon).
  std::optional<FieldPoint> imageToField(const ImagePx& px, double height) const;

  // Undistorted normalised coordinates of a pixel and the radial factor
  // (not positive: no ray, beyond the fold of the distortion).
  double undistortPixel(const ImagePx& px, double* nx, double* ny) const;
  // Distorted normalised coordinates of undistorted ones; false where no
  // pixel of the model's valid part maps there.
  bool distortNormalised(double nx, double ny, double* dx, double* dy) const;

  // Unit viewing direction of a pixel in field coordinates.
  Eigen::Vector3d pixelRay(const ImagePx& px) const;

  // Camera center in field coordinates (C = -R^T t), recomputed from q and t.
  const Eigen::Vector3d& position() const { return position_; }
  // Field->camera rotation as used for field->image.
  const Eigen::Matrix3d& rotation() const { return rot_; }

  // Distorted from undistorted normalised radius (solves k r^3 + r = r_u).
  // Empty when k < 0 and r_u exceeds the largest radius the model reaches.
  static std::optional<double> distortRadius(double r_u, double k);
  // Undistorted from distorted normalised radius: r_d (1 + k r_d^2).
  static double undistortRadius(double r_d, double k) { return r_d * (1 + k * r_d * r_d); }

 private:
  CameraCalibration calib_;
  Eigen::Matrix3d rot_;      // R(q) after SSL-Vision's normalisation rule
  Eigen::Matrix3d rot_inv_;  // R(q^-1), q^-1 = conj(q)/|q|^2
  Eigen::Vector3d t_;
  Eigen::Vector3d position_;
  double lens_[4];               // calib_.lens as an array (k2, k3, p1, p2)
  double fold_r2_ = 1e300;       // lens terms: squared radius where the radial map folds
};

// Rotation matrix of the Hamilton quaternion (x, y, z, w), evaluated with the
// unit-quaternion formula even when |q| != 1, as SSL-Vision does.
Eigen::Matrix3d quaternionMatrix(double x, double y, double z, double w);

}  // namespace dv
