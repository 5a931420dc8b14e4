#include "geometry/calibration/joint_refine.h"

#include <ceres/ceres.h>

#include <cmath>

#include "geometry/calibration/calibration_quality.h"
#include "geometry/calibration/camera_params.h"

namespace dv {

namespace {

// The camera's lens terms (LensTerms) stay as its own fit left them.
struct SharedLineResidual {
  SharedLineResidual(ImagePx px, const FieldLineElement* e, double inv_scale, const double* lens)
      : px(px), e(e), inv_scale(inv_scale), lens(lens) {}
  template <typename T>
  bool operator()(const T* intr, const T* rot, const T* pos, const T* offset, T* r) const {
    T xy[2];
    const T l[4] = {T(lens[0]), T(lens[1]), T(lens[2]), T(lens[3])};
    if (!backProjectPixelLens(intr, l, rot, pos, px.u, px.v, 0.0, xy)) return false;
    r[0] = (e->signedDistance(xy) - offset[0]) * T(inv_scale);
    return true;
  }
  ImagePx px;
  const FieldLineElement* e;
  double inv_scale;
  const double* lens;
};

struct OffsetPrior {
  explicit OffsetPrior(double sigma) : sigma(sigma) {}
  template <typename T>
  bool operator()(const T* o, T* r) const {
    r[0] = o[0] / T(sigma);
    return true;
  }
  double sigma;
};

}  // namespace

JointRefineResult refineJointly(const std::vector<CameraLines>& cams, const FieldModel& field,
                                const JointRefineOptions& o) {
  const FieldLineModel model(field);
  JointRefineResult result;
  for (const auto& c : cams) result.calibrations.push_back(c.calibration);
  result.line_offsets_mm.assign(model.elements().size(), 0.0);
  if (cams.size() < 2) return result;

  std::vector<CameraParams> params;
  std::vector<std::vector<LinePixelMatch>> matches;
  for (const auto& c : cams) {
    params.push_back(CameraParams::fromCalibration(c.calibration));
    std::vector<ImagePx> px;
    const double stride = std::max(1.0, double(c.line_pixels.size()) / o.max_pixels_per_camera);
    for (double i = 0; i < double(c.line_pixels.size()); i += stride) px.push_back(c.line_pixels[size_t(i)]);
    matches.push_back(matchLinePixels(params.back(), px, model, o.gate_px));
  }
  std::vector<double> offsets(model.elements().size(), 0.0);
  // The cost every camera pays on its matched pixels, with the offsets.
  auto cost = [&](const std::vector<CameraParams>& ps, const std::vector<double>& off) {
    double sum = 0;
    size_t n = 0;
    for (size_t c = 0; c < ps.size(); ++c)
      for (const auto& m : matches[c]) {
        double r;
        SharedLineResidual res(m.px, &model.elements()[m.element], 1.0 / m.mm_per_px, ps[c].lens);
        if (!res(ps[c].intrinsics, ps[c].rotation, ps[c].position, &off[m.element], &r)) r = o.gate_px;
        sum += cauchyCost(std::min(std::abs(r), o.gate_px), o.loss_scale_px);
        ++n;
      }
    for (double v : off) sum += 0.5 * (v / o.line_offset_sigma_mm) * (v / o.line_offset_sigma_mm);
    return n ? sum / double(n) : 1e300;
  };
  result.cost_before = cost(params, offsets);

  // Only lines seen by two or more cameras get an offset: for the others it
  // would just absorb that camera's error.
  std::vector<int> seen_by(offsets.size(), 0);
  for (const auto& ms : matches) {
    std::vector<bool> seen(offsets.size(), false);
    for (const auto& m : ms) seen[m.element] = true;
    for (size_t e = 0; e < seen.size(); ++e) seen_by[e] += seen[e] ? 1 : 0;
  }

  std::vector<CameraParams> refined = params;
  ceres::Problem problem;
  ceres::LossFunction* loss = new ceres::CauchyLoss(o.loss_scale_px);
  for (size_t c = 0; c < cams.size(); ++c) {
    auto& p = refined[c];
    for (const auto& m : matches[c])
      problem.AddResidualBlock(
          new ceres::AutoDiffCostFunction<SharedLineResidual, 1, 4, 3, 3, 1>(
              new SharedLineResidual(m.px, &model.elements()[m.element], 1.0 / m.mm_per_px, p.lens)),
          loss, p.intrinsics, p.rotation, p.position, &offsets[m.element]);
    // Principal point and position trade against each other along a nearly
    // flat valley (thesis eq. 5.8); the prior keeps the point near each
    // camera's own fit.
    problem.AddResidualBlock(new ceres::AutoDiffCostFunction<PrincipalPointPrior, 2, 4>(new PrincipalPointPrior(
                                 p.intrinsics[1], p.intrinsics[2], o.principal_point_sigma_px)),
                             nullptr, p.intrinsics);
    if (cams[c].fix_height) problem.SetManifold(p.position, new ceres::SubsetManifold(3, {2}));
  }
  for (size_t e = 0; e < offsets.size(); ++e) {
    if (!problem.HasParameterBlock(&offsets[e])) continue;
    problem.AddResidualBlock(new ceres::AutoDiffCostFunction<OffsetPrior, 1, 1>(
                                 new OffsetPrior(o.line_offset_sigma_mm)),
                             nullptr, &offsets[e]);
    if (seen_by[e] < 2) problem.SetParameterBlockConstant(&offsets[e]);
  }
  ceres::Solver::Options so;
  so.logging_type = ceres::SILENT;
  so.linear_solver_type = ceres::DENSE_QR;
  so.max_num_iterations = 50;
  ceres::Solver::Summary summary;
  ceres::Solve(so, &problem, &summary);
  const double after = cost(refined, offsets);
  // A joint correction is small: a camera whose positions at robot height
  // would move by more than the line offsets allow has slid, not improved.
  bool small = true;
  for (size_t c = 0; c < cams.size(); ++c) {
    const auto& in = cams[c].calibration;
    const CameraCalibration moved = refined[c].toCalibration(in.camera_id, in.image_width, in.image_height);
    const FieldRect everywhere{-1e6, 1e6, -1e6, 1e6};
    if (meanFieldPositionError(in, moved, 150, everywhere, 64) > 3 * o.line_offset_sigma_mm) small = false;
  }
  if (small && std::isfinite(after) && after <= result.cost_before) {
    result.accepted = true;
    result.cost_after = after;
    result.line_offsets_mm = offsets;
    for (size_t c = 0; c < cams.size(); ++c) {
      const auto& in = cams[c].calibration;
      result.calibrations[c] = refined[c].toCalibration(in.camera_id, in.image_width, in.image_height);
    }
  } else {
    result.cost_after = result.cost_before;
  }
  return result;
}

double meanSeamOffset(const CameraCalibration& truth_a, const CameraCalibration& est_a,
                      const CameraCalibration& truth_b, const CameraCalibration& est_b, double height,
                      double step, int* samples) {
  const CameraModel ta(truth_a), ea(est_a), tb(truth_b), eb(est_b);
  auto inside = [](const CameraCalibration& c, const ImagePx& p) {
    return p.u >= 0 && p.v >= 0 && p.u <= c.image_width - 1.0 && p.v <= c.image_height - 1.0;
  };
  double sum = 0;
  int n = 0;
  for (double x = -7000; x <= 7000; x += step)
    for (double y = -5500; y <= 5500; y += step) {
      const FieldPoint p{x, y, height};
      const auto pa = ta.fieldToImage(p), pb = tb.fieldToImage(p);
      if (!pa || !pb || !inside(truth_a, *pa) || !inside(truth_b, *pb)) continue;
      const auto qa = ea.imageToField(*pa, height), qb = eb.imageToField(*pb, height);
      if (!qa || !qb) continue;
      sum += std::hypot(qa->x - qb->x, qa->y - qb->y);
      ++n;
    }
  if (samples) *samples = n;
  return n ? sum / n : 0;
}

}  // namespace dv
