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
#include <Eigen/Core>
#include <cstdint>
#include <optional>

#include "core/units.h"

namespace dv {

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
};

// Rotation matrix of the Hamilton quaternion (x, y, z, w), evaluated with the
// unit-quaternion formula even when |q| != 1, as SSL-Vision does.
Eigen::Matrix3d quaternionMatrix(double x, double y, double z, double w);

}  // namespace dv
