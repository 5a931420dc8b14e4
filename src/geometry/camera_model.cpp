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
  lens_[0] = c.lens.k2, lens_[1] = c.lens.k3, lens_[2] = c.lens.p1, lens_[3] = c.lens.p2;
  if (c.lens.any()) {
    // The radial map r (1 + k1 r^2 + k2 r^4 + k3 r^6) must grow with r; past
    // the first radius where it stops (or its factor reaches 0) there is no
    // lens. Scanned in r^2 to 16 (76 deg off axis), then bisected.
    const double k1 = c.distortion, k2 = c.lens.k2, k3 = c.lens.k3;
    auto ok = [&](double r2) {
      return 1 + r2 * (3 * k1 + r2 * (5 * k2 + r2 * 7 * k3)) > 0 && 1 + r2 * (k1 + r2 * (k2 + r2 * k3)) > 0;
    };
    for (double hi = 0.01; hi <= 16; hi += 0.01) {
      if (ok(hi)) continue;
      double lo = hi - 0.01;
      for (int i = 0; i < 60; ++i) (ok((lo + hi) / 2) ? lo : hi) = (lo + hi) / 2;
      fold_r2_ = lo;
      break;
    }
  }
}

double CameraModel::undistortPixel(const ImagePx& px, double* nx, double* ny) const {
  const double dx = (px.u - calib_.principal_point_x) / calib_.focal_length;
  const double dy = (px.v - calib_.principal_point_y) / calib_.focal_length;
  if (!calib_.lens.any()) {
    // n = d (1 + k |d|^2); equal to SSL-Vision's d * r_u / r_d except at d = 0.
    const double s = 1 + calib_.distortion * (dx * dx + dy * dy);
    *nx = dx * s, *ny = dy * s;
    return s;
  }
  if (!(dx * dx + dy * dy < fold_r2_)) return 0;
  return undistortNormalised(dx, dy, calib_.distortion, lens_, nx, ny);
}

bool CameraModel::distortNormalised(double nx, double ny, double* dx, double* dy) const {
  const double r_u = std::hypot(nx, ny);
  // The league's radial inverse first: the answer without lens terms, and
  // the start of Newton's method with them.
  double x = nx, y = ny;
  if (r_u > 0) {
    const auto r_d = distortRadius(r_u, calib_.distortion);
    if (!r_d && !calib_.lens.any()) return false;
    if (r_d) x = nx * (*r_d / r_u), y = ny * (*r_d / r_u);
  }
  if (!calib_.lens.any()) {
    *dx = x, *dy = y;
    return true;
  }
  const double k1 = calib_.distortion, k2 = lens_[0], k3 = lens_[1], p1 = lens_[2], p2 = lens_[3];
  for (int i = 0; i < 50; ++i) {
    double ux, uy;
    const double r2 = x * x + y * y;
    const double s = undistortNormalised(x, y, k1, lens_, &ux, &uy);
    const double ds = k1 + r2 * (2 * k2 + r2 * 3 * k3);
    const double a = s + 2 * x * x * ds + 2 * p1 * y + 6 * p2 * x;
    const double b = 2 * x * y * ds + 2 * p1 * x + 2 * p2 * y;
    const double d = s + 2 * y * y * ds + 6 * p1 * y + 2 * p2 * x;
    const double det = a * d - b * b;
    if (!(det > 0)) return false;
    const double fx = ux - nx, fy = uy - ny;
    const double sx = (d * fx - b * fy) / det, sy = (a * fy - b * fx) / det;
    x -= sx, y -= sy;
    if (std::abs(sx) + std::abs(sy) <= 1e-15 * std::max(1.0, std::abs(x) + std::abs(y))) break;
  }
  double ux, uy;
  if (!(x * x + y * y < fold_r2_) || !(undistortNormalised(x, y, k1, lens_, &ux, &uy) > 0)) return false;
  if (!(std::abs(ux - nx) + std::abs(uy - ny) <= 1e-9 * std::max(1.0, r_u))) return false;
  *dx = x, *dy = y;
  return true;
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
  if (calib_.lens.any()) {
    double dx, dy;
    if (!distortNormalised(nx, ny, &dx, &dy)) return std::nullopt;
    return ImagePx{calib_.focal_length * dx + calib_.principal_point_x,
                   calib_.focal_length * dy + calib_.principal_point_y};
  }
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
  double nx, ny;
  undistortPixel(px, &nx, &ny);
  const Eigen::Vector3d v = rot_inv_ * Eigen::Vector3d(nx, ny, 1.0);
  return v.normalized();
}

std::optional<FieldPoint> CameraModel::imageToField(const ImagePx& px, double height) const {
  double nx, ny;
  // With k < 0 the model folds back beyond its peak radius: no ray there.
  if (!(undistortPixel(px, &nx, &ny) > 0)) return std::nullopt;
  const Eigen::Vector3d d = (rot_inv_ * Eigen::Vector3d(nx, ny, 1.0)).normalized();
  if (!(std::abs(d.z()) > 1e-12)) return std::nullopt;
  const double s = (height - position_.z()) / d.z();
  if (!(s > 0) || !std::isfinite(s)) return std::nullopt;
  const Eigen::Vector3d p = position_ + s * d;
  return FieldPoint{p.x(), p.y(), p.z()};
}

}  // namespace dv
