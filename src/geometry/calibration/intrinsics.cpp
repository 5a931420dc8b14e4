#include "geometry/calibration/intrinsics.h"

#include <ceres/ceres.h>

#include <cmath>

#include "geometry/camera_model.h"

namespace dv {

ImagePx PixelDistortion::undistort(ImagePx p) const {
  const double dx = p.u - cx, dy = p.v - cy;
  const double s = 1 + kappa * (dx * dx + dy * dy);
  return {cx + dx * s, cy + dy * s};
}

std::optional<ImagePx> PixelDistortion::distort(ImagePx p) const {
  const double dx = p.u - cx, dy = p.v - cy;
  const double r_u = std::hypot(dx, dy);
  if (r_u == 0) return p;
  const auto r_d = CameraModel::distortRadius(r_u, kappa);
  if (!r_d) return std::nullopt;
  const double s = *r_d / r_u;
  return ImagePx{cx + dx * s, cy + dy * s};
}

namespace {

// kappa is scaled so that its parameter is of order one.
struct StraightnessResidual {
  StraightnessResidual(ImagePx p, double kappa_scale) : p(p), kappa_scale(kappa_scale) {}
  template <typename T>
  bool operator()(const T* kappa, const T* center, const T* line, T* r) const {
    const T dx = T(p.u) - center[0], dy = T(p.v) - center[1];
    const T s = T(1) + kappa[0] * T(kappa_scale) * (dx * dx + dy * dy);
    // line = (angle, offset) in undistorted pixels relative to the center.
    r[0] = cos(line[0]) * dx * s + sin(line[0]) * dy * s - line[1];
    return true;
  }
  ImagePx p;
  double kappa_scale;
};

struct CenterPrior {
  CenterPrior(double x, double y, double sigma) : x(x), y(y), sigma(sigma) {}
  template <typename T>
  bool operator()(const T* c, T* r) const {
    r[0] = (c[0] - T(x)) / T(sigma);
    r[1] = (c[1] - T(y)) / T(sigma);
    return true;
  }
  double x, y, sigma;
};

// Total-least-squares line (angle of the normal, offset) through points.
std::array<double, 2> fitLine(const std::vector<ImagePx>& pts, double cx, double cy) {
  double mx = 0, my = 0;
  for (auto p : pts) mx += p.u - cx, my += p.v - cy;
  mx /= pts.size(), my /= pts.size();
  double sxx = 0, syy = 0, sxy = 0;
  for (auto p : pts) {
    const double x = p.u - cx - mx, y = p.v - cy - my;
    sxx += x * x, syy += y * y, sxy += x * y;
  }
  // Direction of largest spread; the normal is perpendicular.
  const double dir = 0.5 * std::atan2(2 * sxy, sxx - syy);
  const double normal = dir + kPi / 2;
  return {normal, std::cos(normal) * mx + std::sin(normal) * my};
}

}  // namespace

std::optional<IntrinsicsResult> calibrateDistortion(const std::vector<LineGroup>& groups,
                                                    int image_width, int image_height,
                                                    const IntrinsicsOptions& o) {
  std::vector<const LineGroup*> used;
  for (const auto& g : groups)
    if (g.extent_px >= o.min_group_extent_px && g.pixels.size() >= 20) used.push_back(&g);
  if (used.size() < 2) return std::nullopt;

  const double half_diag = 0.5 * std::hypot(image_width, image_height);
  const double kappa_scale = 1.0 / (half_diag * half_diag);
  double kappa = 0;
  double center[2] = {(image_width - 1) / 2.0, (image_height - 1) / 2.0};
  std::vector<std::array<double, 2>> lines;
  for (auto* g : used) lines.push_back(fitLine(g->pixels, center[0], center[1]));

  ceres::Problem problem;
  size_t n = 0;
  for (size_t i = 0; i < used.size(); ++i) {
    for (const auto& p : used[i]->pixels) {
      problem.AddResidualBlock(
          new ceres::AutoDiffCostFunction<StraightnessResidual, 1, 1, 2, 2>(
              new StraightnessResidual(p, kappa_scale)),
          new ceres::HuberLoss(2.0), &kappa, center, lines[i].data());
      ++n;
    }
  }
  // The prior's weight grows with the data so that it stays a weak prior.
  problem.AddResidualBlock(new ceres::AutoDiffCostFunction<CenterPrior, 2, 2>(new CenterPrior(
                               center[0], center[1], o.principal_point_sigma_px)),
                           nullptr, center);
  if (!o.fit_principal_point) problem.SetParameterBlockConstant(center);

  auto rms = [&] {
    double sum = 0;
    for (size_t i = 0; i < used.size(); ++i)
      for (const auto& p : used[i]->pixels) {
        double r;
        StraightnessResidual(p, kappa_scale)(&kappa, center, lines[i].data(), &r);
        sum += r * r;
      }
    return std::sqrt(sum / double(n));
  };
  IntrinsicsResult result;
  result.rms_before_px = rms();
  ceres::Solver::Options so;
  so.logging_type = ceres::SILENT;
  so.linear_solver_type = ceres::DENSE_SCHUR;
  so.max_num_iterations = 100;
  so.num_threads = 1;
  ceres::Solver::Summary summary;
  ceres::Solve(so, &problem, &summary);
  result.rms_px = rms();
  result.groups_used = int(used.size());
  result.distortion = {kappa * kappa_scale, center[0], center[1]};
  return result;
}

}  // namespace dv
