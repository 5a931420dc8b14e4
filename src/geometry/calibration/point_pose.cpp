#include "geometry/calibration/point_pose.h"

#include <ceres/ceres.h>

#include <cmath>
#include <opencv2/calib3d.hpp>

namespace dv {

namespace {

struct PointResidual {
  PointResidual(FieldPoint p, ImagePx px) : p(p), px(px) {}
  template <typename T>
  bool operator()(const T* intr, const T* rot, const T* pos, T* r) const {
    return pointReprojection(intr, rot, pos, p, px, r);
  }
  FieldPoint p;
  ImagePx px;
};

double solveFrom(CameraParams& cp, const std::vector<PointCorrespondence>& pts, bool fix_height) {
  ceres::Problem problem;
  for (const auto& c : pts)
    problem.AddResidualBlock(
        new ceres::AutoDiffCostFunction<PointResidual, 2, 4, 3, 3>(new PointResidual(c.field, c.image)),
        nullptr, cp.intrinsics, cp.rotation, cp.position);
  // Only the focal length is free among the intrinsics here.
  problem.SetManifold(cp.intrinsics, new ceres::SubsetManifold(4, {1, 2, 3}));
  if (fix_height) problem.SetManifold(cp.position, new ceres::SubsetManifold(3, {2}));
  problem.SetParameterLowerBound(cp.intrinsics, 0, 10.0);
  ceres::Solver::Options so;
  so.logging_type = ceres::SILENT;
  so.linear_solver_type = ceres::DENSE_QR;
  so.max_num_iterations = 200;
  so.function_tolerance = 1e-14;
  so.parameter_tolerance = 1e-14;
  so.gradient_tolerance = 1e-16;
  ceres::Solver::Summary summary;
  ceres::Solve(so, &problem, &summary);
  if (!std::isfinite(summary.final_cost)) return 1e300;
  // Every point must stay in front of the camera.
  for (const auto& c : pts) {
    if (!inFrontOfCamera(cp.rotation, cp.position, c.field)) return 1e300;
  }
  return summary.final_cost;
}

}  // namespace

std::vector<FieldPoint> regionCornersCounterClockwise(double x0, double x1, double y0, double y1) {
  return {{x0, y0, 0}, {x1, y0, 0}, {x1, y1, 0}, {x0, y1, 0}};
}

std::optional<PointPoseResult> solvePointPose(const std::vector<PointCorrespondence>& pts,
                                              const PixelDistortion& dist,
                                              const PointPoseOptions& o) {
  if (pts.size() < 4) return std::nullopt;
  std::vector<cv::Point3d> object;
  std::vector<cv::Point2d> undistorted;
  for (const auto& c : pts) {
    object.emplace_back(c.field.x, c.field.y, c.field.z);
    const ImagePx u = dist.undistort(c.image);
    undistorted.emplace_back(u.u, u.v);
  }
  bool planar = true;
  for (const auto& c : pts) planar = planar && std::abs(c.field.z) < 1e-9;

  const double width = o.image_width > 0 ? o.image_width : 2 * dist.cx;
  std::optional<PointPoseResult> best;
  double best_cost = 1e300;
  // The focal length is unknown: start from a range of guesses, each with
  // OpenCV's planar pose (IPPE) on the undistorted points.
  for (double f = 0.25 * width; f <= 6 * width; f *= 1.35) {
    const cv::Matx33d K(f, 0, dist.cx, 0, f, dist.cy, 0, 0, 1);
    cv::Mat rvec, tvec;
    bool ok = false;
    try {
      ok = cv::solvePnP(object, undistorted, K, cv::noArray(), rvec, tvec, false,
                        planar ? cv::SOLVEPNP_IPPE : cv::SOLVEPNP_ITERATIVE);
    } catch (const cv::Exception&) {
      ok = false;
    }
    if (!ok) continue;
    cv::Matx33d R;
    cv::Rodrigues(rvec, R);
    const cv::Vec3d t(tvec);
    const cv::Vec3d C = -(R.t() * t);
    if (C[2] <= 0) continue;  // the mirror solution below the field
    CameraParams cp;
    cp.intrinsics[0] = f;
    cp.intrinsics[1] = dist.cx;
    cp.intrinsics[2] = dist.cy;
    cp.intrinsics[3] = dist.k(f);
    for (int i = 0; i < 3; ++i) cp.rotation[i] = rvec.at<double>(i), cp.position[i] = C[i];
    if (o.camera_height_mm) {
      // Scale the start so that the height matches (f/height is what the points fix).
      const double s = *o.camera_height_mm / C[2];
      cp.intrinsics[0] = f * s;
      cp.intrinsics[3] = dist.k(f * s);
      cp.position[2] = *o.camera_height_mm;
    }
    // k follows the focal length: kappa is what the lines observed.
    double cost = 1e300;
    for (int round = 0; round < 4; ++round) {
      cost = solveFrom(cp, pts, o.camera_height_mm.has_value());
      const double k_new = dist.k(cp.intrinsics[0]);
      const bool settled = std::abs(k_new - cp.intrinsics[3]) <= 1e-9 * (1 + std::abs(k_new));
      cp.intrinsics[3] = k_new;
      if (settled) break;
    }
    if (cost < best_cost) {
      best_cost = cost;
      best = PointPoseResult{cp, std::sqrt(2 * cost / double(pts.size()))};
    }
  }
  return best;
}

}  // namespace dv
