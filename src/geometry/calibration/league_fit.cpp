#include "geometry/calibration/league_fit.h"

#include <ceres/ceres.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "geometry/calibration/camera_params.h"

namespace dv {

namespace {

constexpr double kHeights[2] = {0.0, 150.0};

struct Sample {
  ImagePx px;
  double z;
  FieldPoint target;
};

// A 32 x 24 grid of pixels over the image (its size, else twice the
// principal point) where `c` has a ray to both planes.
std::vector<Sample> samples(const CameraCalibration& c) {
  const double w = c.image_width ? c.image_width : 2 * c.principal_point_x + 1;
  const double h = c.image_height ? c.image_height : 2 * c.principal_point_y + 1;
  const CameraModel m(c);
  std::vector<Sample> out;
  constexpr int nu = 32, nv = 24;
  for (int j = 0; j < nv; ++j)
    for (int i = 0; i < nu; ++i) {
      const ImagePx px{(w - 1) * i / (nu - 1), (h - 1) * j / (nv - 1)};
      for (double z : kHeights)
        if (const auto p = m.imageToField(px, z)) out.push_back({px, z, *p});
    }
  return out;
}

struct FieldResidual {
  explicit FieldResidual(const Sample& s) : s(s) {}
  template <typename T>
  bool operator()(const T* intr, const T* rot, const T* pos, T* r) const {
    T xy[2];
    if (!backProjectPixel(intr, rot, pos, s.px.u, s.px.v, s.z, xy)) return false;
    r[0] = xy[0] - T(s.target.x);
    r[1] = xy[1] - T(s.target.y);
    return true;
  }
  Sample s;
};

}  // namespace

ModelDifference modelDifference(const CameraCalibration& a, const CameraCalibration& b) {
  const CameraModel mb(b);
  ModelDifference d;
  double sum = 0;
  for (const Sample& s : samples(a)) {
    const auto q = mb.imageToField(s.px, s.z);
    if (!q) continue;
    const double e = std::hypot(q->x - s.target.x, q->y - s.target.y);
    sum += e, d.max_mm = std::max(d.max_mm, e), ++d.samples;
  }
  if (d.samples) d.mean_mm = sum / d.samples;
  return d;
}

LeagueFit leagueFit(const CameraCalibration& c) {
  if (!c.lens.any()) return {c, {}};
  CameraCalibration start = c;
  start.lens = {};
  CameraParams p = CameraParams::fromCalibration(start);
  ceres::Problem problem;
  for (const Sample& s : samples(c))
    problem.AddResidualBlock(new ceres::AutoDiffCostFunction<FieldResidual, 2, 4, 3, 3>(new FieldResidual(s)),
                             nullptr, p.intrinsics, p.rotation, p.position);
  ceres::Solver::Options so;
  so.logging_type = ceres::SILENT;
  so.linear_solver_type = ceres::DENSE_QR;
  so.max_num_iterations = 50;
  so.num_threads = 1;
  ceres::Solver::Summary summary;
  ceres::Solve(so, &problem, &summary);
  LeagueFit fit;
  fit.calibration = p.intrinsics[0] > 0 && std::isfinite(summary.final_cost)
                        ? p.toCalibration(c.camera_id, c.image_width, c.image_height)
                        : start;
  fit.residual = modelDifference(c, fit.calibration);
  return fit;
}

}  // namespace dv
