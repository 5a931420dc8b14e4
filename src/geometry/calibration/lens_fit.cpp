#include "geometry/calibration/lens_fit.h"

#include <ceres/ceres.h>

#include <algorithm>
#include <cmath>
#include <map>

#include "geometry/calibration/camera_frame.h"

namespace dv {

namespace {

constexpr double kLineOffsetSigmaMm = 15;  // as JointRefineOptions::line_offset_sigma_mm

// The line pixels of a short stretch of one model line (a bin): their mean
// signed distance to the line is where the model puts the painted line's
// center there. The line's width, which dominates single pixels' distances,
// cancels in the mean, so a lens error of a fraction of a pixel shows. Over
// a bin of a few pixels the image-to-field map is linear to about a
// hundredth of a pixel (an arc's sagitta over the bin), so the mean of the
// pixels' distances is the distance of their centroid: one ray per bin
// instead of one per pixel (the fit's time was almost all in those rays'
// iterative undistortion).
struct LineBin {
  ImagePx centroid;
  int element = -1;
  long index = 0;        // position along the element, in bins
  double inv_scale = 0;  // px per mm on the field
};

struct LensBinResidual {
  LensBinResidual(const LineBin* b, const FieldLineElement* e) : b(b), e(e) {}
  // `offset`: where the painted line lies off its nominal place (mm).
  template <typename T>
  bool operator()(const T* intr, const T* lens, const T* rot, const T* pos, const T* offset, T* r) const {
    T xy[2];
    if (!backProjectPixelLens(intr, lens, rot, pos, b->centroid.u, b->centroid.v, 0.0, xy)) return false;
    r[0] = (e->signedDistance(xy) - offset[0]) * T(b->inv_scale);
    return true;
  }
  const LineBin* b;
  const FieldLineElement* e;
};

// Bins of about 4 px along each model line; a bin needs pixels from both
// sides of the line's center to say where it is.
std::vector<LineBin> binMatches(const CameraParams& p, const std::vector<LinePixelMatch>& matches,
                                const FieldLineModel& model, int width, int height) {
  std::vector<double> scales;
  for (const auto& m : matches) scales.push_back(m.mm_per_px);
  std::nth_element(scales.begin(), scales.begin() + scales.size() / 2, scales.end());
  const double bin_mm = 4 * scales[scales.size() / 2];
  struct Sums {
    double u = 0, v = 0, inv_scale = 0;
    int below = 0, above = 0;
  };
  std::map<std::pair<int, long>, Sums> bins;
  for (const auto& m : matches) {
    // A line cut by the image border has lost part of its width.
    if (m.px.u < 8 || m.px.v < 8 || m.px.u > width - 9 || m.px.v > height - 9) continue;
    double xy[2];
    if (!backProjectPixelLens(p.intrinsics, p.lens, p.rotation, p.position, m.px.u, m.px.v, 0.0, xy)) continue;
    const FieldLineElement& e = model.elements()[m.element];
    double t;
    if (e.is_arc) {
      t = std::atan2(xy[1] - e.center.y, xy[0] - e.center.x) * e.radius;
    } else {
      const double len = std::hypot(e.b.x - e.a.x, e.b.y - e.a.y);
      t = ((xy[0] - e.a.x) * (e.b.x - e.a.x) + (xy[1] - e.a.y) * (e.b.y - e.a.y)) / len;
    }
    const std::pair<int, long> key{m.element, long(std::floor(t / bin_mm))};
    Sums& b = bins[key];
    b.u += m.px.u, b.v += m.px.v, b.inv_scale += 1 / m.mm_per_px;
    (e.signedDistance(xy) < 0 ? b.below : b.above)++;
  }
  std::vector<LineBin> out;
  for (const auto& [key, b] : bins) {
    if (b.below < 2 || b.above < 2 || std::abs(b.below - b.above) > std::max(2, (b.below + b.above) / 4)) continue;
    const double n = b.below + b.above;
    LineBin bin;
    bin.centroid = ImagePx{b.u / n, b.v / n};
    bin.element = key.first, bin.index = key.second;
    bin.inv_scale = b.inv_scale / n;
    out.push_back(bin);
  }
  return out;
}

// Residuals of the bins (px) for parameters p.
std::vector<double> binResiduals(const CameraParams& p, const std::vector<double>& offsets,
                                 const std::vector<LineBin>& bins, const FieldLineModel& model) {
  std::vector<double> r;
  r.reserve(bins.size());
  for (const auto& b : bins) {
    double v = 1e3;  // no ray: far off
    LensBinResidual(&b, &model.elements()[b.element])(p.intrinsics, p.lens, p.rotation, p.position,
                                                       &offsets[b.element], &v);
    r.push_back(v);
  }
  return r;
}

double meanCauchy(const std::vector<double>& r, double s) {
  double sum = 0;
  for (double v : r) sum += cauchyCost(v, s);
  return r.empty() ? 0 : sum / double(r.size());
}

// Lag-one correlation of the residuals of neighbouring bins along a line:
// errors the model leaves (rendering, line detection, a lens it lacks) run
// along the lines, so neighbouring bins are not independent samples.
double neighbourCorrelation(const std::vector<LineBin>& bins, const std::vector<double>& r) {
  double sxy = 0, sxx = 0;
  for (size_t i = 0; i + 1 < bins.size(); ++i)
    if (bins[i + 1].element == bins[i].element && bins[i + 1].index == bins[i].index + 1)
      sxy += r[i] * r[i + 1], sxx += 0.5 * (r[i] * r[i] + r[i + 1] * r[i + 1]);
  return sxx > 0 ? sxy / sxx : 0;
}

double rms(const std::vector<double>& r) {
  double sum = 0;
  for (double v : r) sum += v * v;
  return r.empty() ? 0 : std::sqrt(sum / double(r.size()));
}

// A given point against its pixel, in undistorted pixels (as pointReprojection).
struct LensPointResidual {
  LensPointResidual(FieldPoint p, ImagePx px, double sigma) : p(p), px(px), sigma(sigma) {}
  template <typename T>
  bool operator()(const T* intr, const T* lens, const T* rot, const T* pos, T* r) const {
    T pc[3];
    if (!pointInCameraFrame(p, rot, pos, pc)) {
      r[0] = r[1] = T(1e4);
      return true;
    }
    T ux, uy;
    undistortNormalised((T(px.u) - intr[1]) / intr[0], (T(px.v) - intr[2]) / intr[0], intr[3], lens, &ux, &uy);
    r[0] = intr[0] * (ux - pc[0] / pc[2]) / T(sigma);
    r[1] = intr[0] * (uy - pc[1] / pc[2]) / T(sigma);
    return true;
  }
  FieldPoint p;
  ImagePx px;
  double sigma;
};

// Weak prior toward no lens terms: sigma_px of displacement at the image
// corner for each term, so the terms a small view cannot see stay near 0.
// Painted lines lie within a few centimetres of their nominal place (the
// joint refinement's prior): an offset explains a misplaced line in both
// models, so that lens terms are not taken for it.
struct LineOffsetPrior {
  explicit LineOffsetPrior(double sigma) : sigma(sigma) {}
  template <typename T>
  bool operator()(const T* o, T* r) const {
    r[0] = o[0] / T(sigma);
    return true;
  }
  double sigma;
};

struct LensPrior {
  LensPrior(double f, double r, double sigma_px) {
    const double scale[4] = {f * std::pow(r, 5), f * std::pow(r, 7), f * r * r, f * r * r};
    for (int i = 0; i < 4; ++i) w[i] = scale[i] / sigma_px;
  }
  template <typename T>
  bool operator()(const T* lens, T* r) const {
    for (int i = 0; i < 4; ++i) r[i] = lens[i] * T(w[i]);
    return true;
  }
  double w[4];
};

}  // namespace

LensFitResult fitLensOnLines(const CameraParams& league, const std::vector<ImagePx>& all_pixels,
                             const FieldLineModel& model, const std::vector<PointCorrespondence>& points,
                             const LineFitOptions& o) {
  LensFitResult result;
  result.params = result.league = league;
  std::vector<ImagePx> pixels;
  const double stride = std::max(1.0, double(all_pixels.size()) / std::max(1, o.max_pixels));
  for (double i = 0; i < double(all_pixels.size()); i += stride) pixels.push_back(all_pixels[size_t(i)]);
  const double gate = o.gates_px.empty() ? 3.0 : o.gates_px.back();
  const auto matches = matchLinePixels(league, pixels, model, gate);
  if (matches.size() < 200) return result;
  const double w = o.image_width > 0 ? o.image_width : 2 * league.intrinsics[1];
  const double h = o.image_height > 0 ? o.image_height : 2 * league.intrinsics[2];
  const std::vector<LineBin> bins = binMatches(league, matches, model, int(w), int(h));
  result.pixels = int(bins.size());
  if (bins.size() < 50) return result;

  const double corner_r = 0.5 * std::hypot(w, h) / league.intrinsics[0];
  // The same objective for both models (bins, points, priors), so that the
  // comparison is between nested fits and not against a start that another
  // objective (single pixels) optimised.
  const auto solve = [&](CameraParams& cp, std::vector<double>& offsets, bool with_lens) {
    ceres::Problem problem;
    ceres::LossFunction* loss = new ceres::CauchyLoss(o.loss_scale_px);
    for (const auto& b : bins)
      problem.AddResidualBlock(new ceres::AutoDiffCostFunction<LensBinResidual, 1, 4, 4, 3, 3, 1>(
                                   new LensBinResidual(&b, &model.elements()[b.element])),
                               loss, cp.intrinsics, cp.lens, cp.rotation, cp.position, &offsets[b.element]);
    for (auto& v : offsets)
      if (problem.HasParameterBlock(&v))
        problem.AddResidualBlock(new ceres::AutoDiffCostFunction<LineOffsetPrior, 1, 1>(
                                     new LineOffsetPrior(kLineOffsetSigmaMm)),
                                 nullptr, &v);
    for (const auto& pt : points)
      problem.AddResidualBlock(new ceres::AutoDiffCostFunction<LensPointResidual, 2, 4, 4, 3, 3>(
                                   new LensPointResidual(pt.field, pt.image, o.point_sigma_px)),
                               new ceres::HuberLoss(2.0), cp.intrinsics, cp.lens, cp.rotation, cp.position);
    // The principal point near the sensor's center: with tangential terms the
    // lines no longer fix it (a decentred lens bends them as a shifted center
    // would), and lenses are centred on their sensor far better than their
    // distortion is.
    problem.AddResidualBlock(new ceres::AutoDiffCostFunction<PrincipalPointPrior, 2, 4>(new PrincipalPointPrior(
                                 (w - 1) / 2, (h - 1) / 2, o.principal_point_sigma_px)),
                             nullptr, cp.intrinsics);
    problem.AddResidualBlock(
        new ceres::AutoDiffCostFunction<LensPrior, 4, 4>(new LensPrior(league.intrinsics[0], corner_r, 10.0)),
        nullptr, cp.lens);
    if (!with_lens) problem.SetParameterBlockConstant(cp.lens);
    std::vector<int> fixed_intr;
    if (!o.fit_principal_point) fixed_intr.push_back(1), fixed_intr.push_back(2);
    if (!o.fit_distortion) fixed_intr.push_back(3);
    if (!fixed_intr.empty()) problem.SetManifold(cp.intrinsics, new ceres::SubsetManifold(4, fixed_intr));
    if (o.fix_height) problem.SetManifold(cp.position, new ceres::SubsetManifold(3, {2}));
    // The terms correct the league fit; they may not carry the camera along
    // a direction the lines do not fix (the height of a view from straight
    // above): focal length and height stay within a quarter of the start.
    problem.SetParameterLowerBound(cp.intrinsics, 0, 0.8 * league.intrinsics[0]);
    problem.SetParameterUpperBound(cp.intrinsics, 0, 1.25 * league.intrinsics[0]);
    if (!o.fix_height) {
      problem.SetParameterLowerBound(cp.position, 2, 0.8 * league.position[2]);
      problem.SetParameterUpperBound(cp.position, 2, 1.25 * league.position[2]);
    }
    ceres::Solver::Options so;
    so.logging_type = ceres::SILENT;
    so.linear_solver_type = ceres::DENSE_QR;
    so.max_num_iterations = 60;
    so.num_threads = 1;
    ceres::Solver::Summary summary;
    ceres::Solve(so, &problem, &summary);
    if (!std::isfinite(summary.final_cost) || cp.intrinsics[0] <= 0) return false;
    // A fit that ran into those bounds followed an unobservable direction.
    const auto atBound = [](double v, double v0) {
      return std::abs(v / v0 - 0.8) < 1e-3 || std::abs(v / v0 - 1.25) < 1e-3;
    };
    return !atBound(cp.intrinsics[0], league.intrinsics[0]) &&
           (o.fix_height || !atBound(cp.position[2], league.position[2]));
  };
  CameraParams plain = league, cp = league;
  std::vector<double> plain_offsets(model.elements().size(), 0.0);
  if (!solve(plain, plain_offsets, false)) return result;
  cp = plain;
  std::vector<double> offsets = plain_offsets;
  if (!solve(cp, offsets, true)) return result;
  const std::vector<double> r0 = binResiduals(plain, plain_offsets, bins, model);
  result.league_rms_px = result.lens_rms_px = rms(r0);
  const std::vector<double> r1 = binResiduals(cp, offsets, bins, model);
  const double c0 = meanCauchy(r0, o.loss_scale_px), c1 = meanCauchy(r1, o.loss_scale_px);
  // The criterion counts independent samples: n (1 - rho) / (1 + rho) for
  // residuals correlated as a first-order autoregression along the lines.
  const double rho = std::clamp(neighbourCorrelation(bins, r1), 0.0, 0.99);
  const double n = double(bins.size()) * (1 - rho) / (1 + rho);
  result.information_gain = -(n * std::log(c1 / c0) + 4 * std::log(n));
  if (std::isfinite(result.information_gain) && result.information_gain > 0) {
    result.lens_used = true;
    result.params = cp;
    result.lens_rms_px = rms(r1);
  }
  return result;
}

}  // namespace dv
