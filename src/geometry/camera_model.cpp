#include "geometry/camera_model.h"

#include <Eigen/Geometry>
#include <cmath>

namespace dv {

Eigen::Matrix3d quaternionMatrix(double x, double y, double z, double w) {
  Eigen::Matrix3d r;
  r << 1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y),
      2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x),
      2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y);
  return r;
}

CameraCalibration CameraCalibration::fromPose(uint32_t id, double focal, double cx, double cy,
                                              double k, const Eigen::Matrix3d& field_to_camera,
                                              const Eigen::Vector3d& position) {
  CameraCalibration c;
  c.camera_id = id;
  c.focal_length = focal;
  c.principal_point_x = cx;
  c.principal_point_y = cy;
  c.distortion = k;
  Eigen::Quaterniond q(field_to_camera);
  q.normalize();
  c.q0 = q.x();
  c.q1 = q.y();
  c.q2 = q.z();
  c.q3 = q.w();
  const Eigen::Vector3d t = -field_to_camera * position;
  c.tx = t.x();
  c.ty = t.y();
  c.tz = t.z();
  return c;
}

CameraModel::CameraModel(const CameraCalibration& c) : calib_(c) {
  double x = c.q0, y = c.q1, z = c.q2, w = c.q3;
  const double n2 = x * x + y * y + z * z + w * w;
  // SSL-Vision renormalises only when the squared norm is off by more than 1e-6.
  if (std::abs(1.0 - n2) > 1e-6 && n2 > 0) {
    const double n = std::sqrt(n2);
    x /= n, y /= n, z /= n, w /= n;
  }
  rot_ = quaternionMatrix(x, y, z, w);
  const double m2 = x * x + y * y + z * z + w * w;
  rot_inv_ = quaternionMatrix(-x / m2, -y / m2, -z / m2, w / m2);
  t_ = Eigen::Vector3d(c.tx, c.ty, c.tz);
  position_ = rot_inv_ * (-t_);
}

std::optional<double> CameraModel::distortRadius(double r_u, double k) {
  if (k == 0 || r_u == 0) return r_u;
  if (k < 0) {
    // r (1 + k r^2) peaks at r = 1/sqrt(-3k); beyond its maximum there is no
    // image point for this ray.
    const double r_peak = 1.0 / std::sqrt(-3 * k);
    if (r_u > undistortRadius(r_peak, k)) return std::nullopt;
  }
  // Newton on g(r) = k r^3 + r - r_u from r = r_u. g is monotone on the
  // branch we want and convex (k > 0) or concave (k < 0) there, so the
  // iteration approaches the root from one side without overshooting.
  double r = r_u;
  for (int i = 0; i < 100; ++i) {
    const double g = k * r * r * r + r - r_u;
    const double dg = 3 * k * r * r + 1;
    if (dg <= 0) return std::nullopt;
    const double step = g / dg;
    r -= step;
    if (std::abs(step) <= 1e-16 * std::max(1.0, r)) break;
  }
  return r;
}

std::optional<ImagePx> CameraModel::fieldToImage(const FieldPoint& p) const {
  const Eigen::Vector3d pc = rot_ * Eigen::Vector3d(p.x, p.y, p.z) + t_;
  if (!(pc.z() > 0)) return std::nullopt;
  const double nx = pc.x() / pc.z(), ny = pc.y() / pc.z();
  const double r_u = std::hypot(nx, ny);
  double scale = 1;
  if (r_u > 0) {
    const auto r_d = distortRadius(r_u, calib_.distortion);
    if (!r_d) return std::nullopt;
    scale = *r_d / r_u;
  }
  return ImagePx{calib_.focal_length * nx * scale + calib_.principal_point_x,
                 calib_.focal_length * ny * scale + calib_.principal_point_y};
}

Eigen::Vector3d CameraModel::pixelRay(const ImagePx& px) const {
  const double dx = (px.u - calib_.principal_point_x) / calib_.focal_length;
  const double dy = (px.v - calib_.principal_point_y) / calib_.focal_length;
  // n = d (1 + k |d|^2); equal to SSL-Vision's d * r_u / r_d except at d = 0.
  const double s = 1 + calib_.distortion * (dx * dx + dy * dy);
  const Eigen::Vector3d v = rot_inv_ * Eigen::Vector3d(dx * s, dy * s, 1.0);
  return v.normalized();
}

std::optional<FieldPoint> CameraModel::imageToField(const ImagePx& px, double height) const {
  const double dx = (px.u - calib_.principal_point_x) / calib_.focal_length;
  const double dy = (px.v - calib_.principal_point_y) / calib_.focal_length;
  // With k < 0 the model folds back beyond its peak radius: no ray there.
  if (!(1 + calib_.distortion * (dx * dx + dy * dy) > 0)) return std::nullopt;
  const Eigen::Vector3d d = pixelRay(px);
  if (!(std::abs(d.z()) > 1e-12)) return std::nullopt;
  const double s = (height - position_.z()) / d.z();
  if (!(s > 0) || !std::isfinite(s)) return std::nullopt;
  const Eigen::Vector3d p = position_ + s * d;
  return FieldPoint{p.x(), p.y(), p.z()};
}

}  // namespace dv
