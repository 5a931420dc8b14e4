#include "geometry/calibration/line_fit.h"

#include <ceres/ceres.h>

#include <cmath>

namespace dv {

namespace {

struct LinePixelResidual {
  LinePixelResidual(ImagePx px, const FieldLineElement* e, double inv_scale)
      : px(px), e(e), inv_scale(inv_scale) {}
  template <typename T>
  bool operator()(const T* intr, const T* rot, const T* pos, T* r) const {
    T xy[2];
    if (!backProjectPixel(intr, rot, pos, px.u, px.v, 0.0, xy)) return false;
    r[0] = e->signedDistance(xy) * T(inv_scale);
    return true;
  }
  ImagePx px;
  const FieldLineElement* e;
  double inv_scale;
};

struct PointResidual {
  PointResidual(FieldPoint p, ImagePx px, double sigma) : p(p), px(px), sigma(sigma) {}
  template <typename T>
  bool operator()(const T* intr, const T* rot, const T* pos, T* r) const {
    if (!pointReprojection(intr, rot, pos, p, px, r)) return false;
    r[0] /= T(sigma), r[1] /= T(sigma);
    return true;
  }
  FieldPoint p;
  ImagePx px;
  double sigma;
};

using Match = LinePixelMatch;

}  // namespace

std::vector<LinePixelMatch> matchLinePixels(const CameraParams& p, const std::vector<ImagePx>& pixels,
                               const FieldLineModel& model, double gate_px) {
  std::vector<Match> out;
  out.reserve(pixels.size());
  for (const auto& px : pixels) {
    double a[2], b[2], c[2];
    if (!backProjectPixelLens(p.intrinsics, p.lens, p.rotation, p.position, px.u, px.v, 0.0, a)) continue;
    if (!backProjectPixelLens(p.intrinsics, p.lens, p.rotation, p.position, px.u + 1, px.v, 0.0, b)) continue;
    if (!backProjectPixelLens(p.intrinsics, p.lens, p.rotation, p.position, px.u, px.v + 1, 0.0, c)) continue;
    const double scale = 0.5 * (std::hypot(b[0] - a[0], b[1] - a[1]) + std::hypot(c[0] - a[0], c[1] - a[1]));
    if (!(scale > 0) || !std::isfinite(scale)) continue;
    const auto m = model.nearest({a[0], a[1]});
    if (m.element < 0) continue;
    const double d_px = m.distance / scale;
    if (d_px <= gate_px) out.push_back({px, m.element, scale, d_px});
  }
  return out;
}

namespace {

}  // namespace

double robustLineCost(const CameraParams& p, const std::vector<ImagePx>& pixels,
                      const FieldLineModel& model, double gate_px, double loss_scale_px,
                      int* matched) {
  const auto m = matchLinePixels(p, pixels, model, gate_px);
  if (matched) *matched = int(m.size());
  if (m.empty()) return 1e300;
  // Unmatched pixels count as far away, so that sliding off the lines to
  // match fewer pixels cannot look better.
  double sum = 0;
  for (const auto& x : m) sum += cauchyCost(x.distance_px, loss_scale_px);
  sum += double(pixels.size() - m.size()) * cauchyCost(gate_px, loss_scale_px);
  return sum / double(pixels.size());
}

LineFitResult refineOnLines(const CameraParams& start, const std::vector<ImagePx>& all_pixels,
                            const FieldLineModel& model,
                            const std::vector<PointCorrespondence>& points,
                            const LineFitOptions& o) {
  std::vector<ImagePx> pixels;
  {
    const double stride = std::max(1.0, double(all_pixels.size()) / std::max(1, o.max_pixels));
    for (double i = 0; i < double(all_pixels.size()); i += stride) pixels.push_back(all_pixels[size_t(i)]);
  }
  LineFitResult result;
  result.params = start;
  const double final_gate = o.gates_px.empty() ? 3.0 : o.gates_px.back();
  result.cost_before = robustLineCost(start, pixels, model, final_gate, o.loss_scale_px);
  CameraParams cp = start;
  const double cx0 = start.intrinsics[1], cy0 = start.intrinsics[2];
  for (double gate : o.gates_px) {
    for (int round = 0; round < 2; ++round) {
      const auto matches = matchLinePixels(cp, pixels, model, gate);
      if (matches.size() < 50) break;
      ceres::Problem problem;
      ceres::LossFunction* loss = new ceres::CauchyLoss(o.loss_scale_px);
      for (const auto& m : matches)
        problem.AddResidualBlock(
            new ceres::AutoDiffCostFunction<LinePixelResidual, 1, 4, 3, 3>(
                new LinePixelResidual(m.px, &model.elements()[m.element], 1.0 / m.mm_per_px)),
            loss, cp.intrinsics, cp.rotation, cp.position);
      for (const auto& pt : points)
        problem.AddResidualBlock(new ceres::AutoDiffCostFunction<PointResidual, 2, 4, 3, 3>(
                                     new PointResidual(pt.field, pt.image, o.point_sigma_px)),
                                 new ceres::HuberLoss(2.0), cp.intrinsics, cp.rotation, cp.position);
      problem.AddResidualBlock(new ceres::AutoDiffCostFunction<PrincipalPointPrior, 2, 4>(
                                   new PrincipalPointPrior(cx0, cy0, o.principal_point_sigma_px)),
                               nullptr, cp.intrinsics);
      std::vector<int> fixed_intr;
      if (!o.fit_principal_point) fixed_intr.push_back(1), fixed_intr.push_back(2);
      if (!o.fit_distortion) fixed_intr.push_back(3);
      if (!fixed_intr.empty()) problem.SetManifold(cp.intrinsics, new ceres::SubsetManifold(4, fixed_intr));
      if (o.fix_height) problem.SetManifold(cp.position, new ceres::SubsetManifold(3, {2}));
      ceres::Solver::Options so;
      so.logging_type = ceres::SILENT;
      so.linear_solver_type = ceres::DENSE_QR;
      so.max_num_iterations = 30;
      so.num_threads = 1;
      ceres::Solver::Summary summary;
      const CameraParams before = cp;
      ceres::Solve(so, &problem, &summary);
      if (!std::isfinite(summary.final_cost) || cp.intrinsics[0] <= 0) cp = before;
    }
  }
  result.cost_after = robustLineCost(cp, pixels, model, final_gate, o.loss_scale_px, &result.pixels_used);
  result.improved = result.cost_after < result.cost_before;
  if (result.improved) result.params = cp;
  else result.cost_after = result.cost_before;
  return result;
}

}  // namespace dv
