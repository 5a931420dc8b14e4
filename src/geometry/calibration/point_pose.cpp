#include "geometry/calibration/point_pose.h"

#include <ceres/ceres.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <opencv2/calib3d.hpp>

#include "geometry/calibration/camera_frame.h"

namespace dv {

namespace {

// With the distortion fixed in pixel units (kappa), an image point
// undistorts the same whatever the focal length, so the pose is a pinhole
// fit to the undistorted points; k = kappa f^2 follows exactly afterwards.
struct PinholeResidual {
  PinholeResidual(FieldPoint p, ImagePx undistorted, double cx, double cy) : p(p), q(undistorted), cx(cx), cy(cy) {}
  template <typename T>
  bool operator()(const T* f, const T* rot, const T* pos, T* r) const {
    T pc[3];
    if (!pointInCameraFrame(p, rot, pos, pc)) {
      r[0] = r[1] = T(1e4);
      return true;
    }
    r[0] = T(cx) + f[0] * pc[0] / pc[2] - T(q.u);
    r[1] = T(cy) + f[0] * pc[1] / pc[2] - T(q.v);
    return true;
  }
  FieldPoint p;
  ImagePx q;
  double cx, cy;
};

struct PoseStart {
  double f;
  double rotation[3];
  double position[3];
};

double solveFrom(PoseStart& s, const std::vector<PointCorrespondence>& pts, const std::vector<ImagePx>& undistorted,
                 const PixelDistortion& d, bool fix_height) {
  ceres::Problem problem;
  for (size_t i = 0; i < pts.size(); ++i)
    problem.AddResidualBlock(new ceres::AutoDiffCostFunction<PinholeResidual, 2, 1, 3, 3>(
                                 new PinholeResidual(pts[i].field, undistorted[i], d.cx, d.cy)),
                             nullptr, &s.f, s.rotation, s.position);
  if (fix_height) problem.SetManifold(s.position, new ceres::SubsetManifold(3, {2}));
  problem.SetParameterLowerBound(&s.f, 0, 10.0);
  ceres::Solver::Options so;
  so.logging_type = ceres::SILENT;
  so.linear_solver_type = ceres::DENSE_QR;
  so.max_num_iterations = 200;
  so.function_tolerance = 1e-16;
  so.parameter_tolerance = 1e-16;
  so.gradient_tolerance = 1e-20;
  ceres::Solver::Summary summary;
  ceres::Solve(so, &problem, &summary);
  if (!std::isfinite(summary.final_cost)) return 1e300;
  // Every point must stay in front of the camera.
  for (const auto& c : pts)
    if (!inFrontOfCamera(s.rotation, s.position, c.field)) return 1e300;
  return summary.final_cost;
}

// The pose a plane-to-image homography implies for focal length f (Zhang):
// K^-1 H = lambda [r1 r2 t]. Empty for the mirror image of the field.
std::optional<PoseStart> poseFromHomography(const cv::Matx33d& h, double f, const std::vector<PointCorrespondence>& pts) {
  const cv::Matx33d k_inv(1 / f, 0, 0, 0, 1 / f, 0, 0, 0, 1);
  const cv::Matx33d m = k_inv * h;
  const cv::Vec3d m1(m(0, 0), m(1, 0), m(2, 0)), m2(m(0, 1), m(1, 1), m(2, 1)), m3(m(0, 2), m(1, 2), m(2, 2));
  double lambda = 2 / (cv::norm(m1) + cv::norm(m2));
  // The points must come out in front of the camera.
  double depth = 0;
  for (const auto& c : pts) depth += (m1 * c.field.x + m2 * c.field.y + m3)[2];
  if (depth < 0) lambda = -lambda;
  const cv::Vec3d r1 = lambda * m1, r2 = lambda * m2, r3 = r1.cross(r2), t = lambda * m3;
  cv::Matx33d r(r1[0], r2[0], r3[0], r1[1], r2[1], r3[1], r1[2], r2[2], r3[2]);
  // Nearest rotation.
  cv::Mat w, u, vt;
  cv::SVD::compute(cv::Mat(r), w, u, vt);
  r = cv::Matx33d(cv::Mat(u * vt));
  if (cv::determinant(r) < 0) return std::nullopt;
  const cv::Vec3d c = -(r.t() * t);
  if (!(c[2] > 0)) return std::nullopt;  // the camera would be under the field
  PoseStart s;
  s.f = f;
  cv::Vec3d rvec;
  cv::Rodrigues(r, rvec);
  for (int i = 0; i < 3; ++i) s.rotation[i] = rvec[i], s.position[i] = c[i];
  return s;
}

// Starts from the homography of planar points: the focal length from the
// orthogonality of the rotation's first two columns, or, where that is
// ill-conditioned (looking straight down), from the given height.
std::vector<PoseStart> homographyStarts(const std::vector<PointCorrespondence>& pts,
                                        const std::vector<ImagePx>& undistorted, const PixelDistortion& d,
                                        std::optional<double> height) {
  std::vector<cv::Point2d> src, dst;
  for (size_t i = 0; i < pts.size(); ++i)
    src.emplace_back(pts[i].field.x, pts[i].field.y), dst.emplace_back(undistorted[i].u - d.cx, undistorted[i].v - d.cy);
  cv::Mat hm;
  try {
    hm = cv::findHomography(src, dst, 0);
  } catch (const cv::Exception&) {
    return {};
  }
  if (hm.empty()) return {};
  cv::Matx33d h(hm);
  h *= 1.0 / cv::norm(h);
  std::vector<PoseStart> out;
  // (h1 . h2)_K = 0 and |h1|_K = |h2|_K in w = 1/f^2: a w + b = 0 twice.
  const double a1 = h(0, 0) * h(0, 1) + h(1, 0) * h(1, 1), b1 = h(2, 0) * h(2, 1);
  const double a2 = h(0, 0) * h(0, 0) + h(1, 0) * h(1, 0) - h(0, 1) * h(0, 1) - h(1, 1) * h(1, 1);
  const double b2 = h(2, 0) * h(2, 0) - h(2, 1) * h(2, 1);
  const double den = a1 * a1 + a2 * a2;
  const double w = den > 0 ? -(a1 * b1 + a2 * b2) / den : 0;
  if (w > 0 && std::isfinite(w))
    if (auto s = poseFromHomography(h, 1 / std::sqrt(w), pts)) out.push_back(*s);
  if (height) {
    // Straight down the height scales with f; a few fixed-point steps.
    double f = 1000;
    for (int i = 0; i < 8; ++i) {
      const auto s = poseFromHomography(h, f, pts);
      if (!s) break;
      f *= *height / s->position[2];
      if (i == 7) {
        auto last = poseFromHomography(h, f, pts);
        if (last) out.push_back(*last);
      }
    }
  }
  return out;
}

struct Xy {
  double x, y;
};

// Distance of the farthest-off point of a triangle from the line through the
// other two: zero for collinear points.
double offLineDistance(const Xy& a, const Xy& b, const Xy& c) {
  const double cross = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
  const double base = std::max({std::hypot(b.x - a.x, b.y - a.y), std::hypot(c.x - a.x, c.y - a.y),
                                std::hypot(c.x - b.x, c.y - b.y)});
  return base > 0 ? std::abs(cross) / base : 0;
}

// Over every four of the points, the largest of their smallest off-line
// distance: how far the best four are from having three on one line.
double bestGeneralPosition(const std::vector<Xy>& p) {
  double best = 0;
  const size_t n = p.size();
  for (size_t a = 0; a < n; ++a)
    for (size_t b = a + 1; b < n; ++b)
      for (size_t c = b + 1; c < n; ++c)
        for (size_t d = c + 1; d < n; ++d)
          best = std::max(best, std::min({offLineDistance(p[a], p[b], p[c]), offLineDistance(p[a], p[b], p[d]),
                                          offLineDistance(p[a], p[c], p[d]), offLineDistance(p[b], p[c], p[d])}));
  return best;
}

double span(const std::vector<Xy>& p) {
  double s = 0;
  for (size_t i = 0; i < p.size(); ++i)
    for (size_t j = i + 1; j < p.size(); ++j) s = std::max(s, std::hypot(p[i].x - p[j].x, p[i].y - p[j].y));
  return s;
}

}  // namespace

std::optional<std::string> pointSetProblem(const std::vector<PointCorrespondence>& pts, int width, int height) {
  char buf[256];
  if (pts.size() < 4) return "four or more points are needed, got " + std::to_string(pts.size());
  std::vector<Xy> field, image;
  for (const auto& c : pts) field.push_back({c.field.x, c.field.y}), image.push_back({c.image.u, c.image.v});
  for (size_t i = 0; i < pts.size(); ++i)
    for (size_t j = i + 1; j < pts.size(); ++j)
      if (std::hypot(pts[i].field.x - pts[j].field.x, pts[i].field.y - pts[j].field.y) < 1 &&
          std::abs(pts[i].field.z - pts[j].field.z) < 1) {
        std::snprintf(buf, sizeof buf, "field point (%.0f, %.0f) is given twice", pts[i].field.x, pts[i].field.y);
        return std::string(buf);
      }
  // Clicks a few pixels off move a pose from bunched points a long way.
  const double image_span = span(image), min_span = 0.15 * std::min(width, height);
  if (image_span < min_span) {
    std::snprintf(buf, sizeof buf,
                  "the points lie too close together in the image (%.0f px apart, at least %.0f px needed); "
                  "spread them over the image",
                  image_span, min_span);
    return std::string(buf);
  }
  const double field_off = bestGeneralPosition(field) / span(field);
  const double image_off = bestGeneralPosition(image) / image_span;
  if (field_off < 0.05 || image_off < 0.05) {
    std::snprintf(buf, sizeof buf,
                  "no four of the points are clear of one line (%s: the best four are %.1f%% of their spread "
                  "off it, 5%% needed); give four points with no three on one line",
                  field_off < image_off ? "on the field" : "in the image", 100 * std::min(field_off, image_off));
    return std::string(buf);
  }
  return std::nullopt;
}

std::vector<FieldPoint> regionCornersCounterClockwise(double x0, double x1, double y0, double y1) {
  return {{x0, y0, 0}, {x1, y0, 0}, {x1, y1, 0}, {x0, y1, 0}};
}

std::optional<PointPoseResult> solvePointPose(const std::vector<PointCorrespondence>& pts,
                                              const PixelDistortion& dist, const PointPoseOptions& o) {
  if (pts.size() < 4) return std::nullopt;
  std::vector<cv::Point3d> object;
  std::vector<cv::Point2d> image;
  std::vector<ImagePx> undistorted;
  bool planar = true;
  for (const auto& c : pts) {
    object.emplace_back(c.field.x, c.field.y, c.field.z);
    undistorted.push_back(dist.undistort(c.image));
    image.emplace_back(undistorted.back().u, undistorted.back().v);
    planar = planar && std::abs(c.field.z) < 1e-9;
  }
  std::vector<PoseStart> starts;
  if (planar) starts = homographyStarts(pts, undistorted, dist, o.camera_height_mm);
  // Also a range of focal length guesses, each with OpenCV's pose for it
  // (IPPE on planar points), for points off the plane and as a fallback.
  const double width = o.image_width > 0 ? o.image_width : 2 * dist.cx;
  for (double f = 0.25 * width; f <= 6 * width; f *= 1.35) {
    const cv::Matx33d K(f, 0, dist.cx, 0, f, dist.cy, 0, 0, 1);
    cv::Mat rvec, tvec;
    bool ok = false;
    try {
      ok = cv::solvePnP(object, image, K, cv::noArray(), rvec, tvec, false,
                        planar ? cv::SOLVEPNP_IPPE : cv::SOLVEPNP_ITERATIVE);
    } catch (const cv::Exception&) {
      ok = false;
    }
    if (!ok) continue;
    cv::Matx33d R;
    cv::Rodrigues(rvec, R);
    const cv::Vec3d C = -(R.t() * cv::Vec3d(tvec));
    if (C[2] <= 0) continue;  // the mirror solution below the field
    PoseStart s;
    s.f = f;
    for (int i = 0; i < 3; ++i) s.rotation[i] = rvec.at<double>(i), s.position[i] = C[i];
    starts.push_back(s);
  }
  std::optional<PointPoseResult> best;
  double best_cost = 1e300;
  for (auto s : starts) {
    if (o.camera_height_mm) {
      // Scale the start so that the height matches (f/height is what the points fix).
      s.f *= *o.camera_height_mm / s.position[2];
      s.position[2] = *o.camera_height_mm;
    }
    const double cost = solveFrom(s, pts, undistorted, dist, o.camera_height_mm.has_value());
    if (!(cost < best_cost)) continue;
    best_cost = cost;
    CameraParams cp;
    cp.intrinsics[0] = s.f;
    cp.intrinsics[1] = dist.cx;
    cp.intrinsics[2] = dist.cy;
    cp.intrinsics[3] = dist.k(s.f);
    for (int i = 0; i < 3; ++i) cp.rotation[i] = s.rotation[i], cp.position[i] = s.position[i];
    best = PointPoseResult{cp, std::sqrt(2 * cost / double(pts.size()))};
  }
  return best;
}

}  // namespace dv
