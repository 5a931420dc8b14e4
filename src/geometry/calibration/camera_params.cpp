#include "geometry/calibration/camera_params.h"

#include <Eigen/Core>

namespace dv {

CameraParams CameraParams::fromCalibration(const CameraCalibration& c) {
  CameraParams p;
  const CameraModel model(c);
  p.intrinsics[0] = c.focal_length;
  p.intrinsics[1] = c.principal_point_x;
  p.intrinsics[2] = c.principal_point_y;
  p.intrinsics[3] = c.distortion;
  p.lens[0] = c.lens.k2, p.lens[1] = c.lens.k3, p.lens[2] = c.lens.p1, p.lens[3] = c.lens.p2;
  // Ceres wants a row-major matrix here.
  const Eigen::Matrix<double, 3, 3, Eigen::RowMajor> r = model.rotation();
  ceres::RotationMatrixToAngleAxis(ceres::RowMajorAdapter3x3(r.data()), p.rotation);
  const Eigen::Vector3d& pos = model.position();
  p.position[0] = pos.x(), p.position[1] = pos.y(), p.position[2] = pos.z();
  return p;
}

CameraCalibration CameraParams::toCalibration(uint32_t camera_id, uint32_t width,
                                              uint32_t height) const {
  Eigen::Matrix<double, 3, 3, Eigen::RowMajor> r;
  ceres::AngleAxisToRotationMatrix(rotation, ceres::RowMajorAdapter3x3(r.data()));
  CameraCalibration c = CameraCalibration::fromPose(
      camera_id, intrinsics[0], intrinsics[1], intrinsics[2], intrinsics[3], r,
      Eigen::Vector3d(position[0], position[1], position[2]));
  c.image_width = width;
  c.image_height = height;
  c.lens = {lens[0], lens[1], lens[2], lens[3]};
  return c;
}

}  // namespace dv
