#include "geometry/calibration/pose_uncertainty.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <map>
#include <tuple>

#include "geometry/calibration/line_fit.h"

namespace dv {

namespace {

constexpr int kParams = 10;  // f, cx, cy, k, rotation (3), position (3)

void unpack(const Eigen::Matrix<double, kParams, 1>& x, CameraParams& p) {
  for (int i = 0; i < 4; ++i) p.intrinsics[i] = x[i];
  for (int i = 0; i < 3; ++i) p.rotation[i] = x[4 + i], p.position[i] = x[7 + i];
}

Eigen::Matrix<double, kParams, 1> pack(const CameraParams& p) {
  Eigen::Matrix<double, kParams, 1> x;
  for (int i = 0; i < 4; ++i) x[i] = p.intrinsics[i];
  for (int i = 0; i < 3; ++i) x[4 + i] = p.rotation[i], x[7 + i] = p.position[i];
  return x;
}

// Central-difference steps, about a thousandth of each parameter's effect.
Eigen::Matrix<double, kParams, 1> steps(const CameraParams& p) {
  Eigen::Matrix<double, kParams, 1> h;
  h << 1e-4 * p.intrinsics[0], 0.01, 0.01, 1e-5, 1e-6, 1e-6, 1e-6, 0.1, 0.1, 0.1;
  return h;
}

}  // namespace

std::optional<PredictedFieldError> predictFieldError(const CameraParams& params,
                                                     const std::vector<ImagePx>& all_pixels,
                                                     const FieldLineModel& model, const FieldRect& area,
                                                     const PoseUncertaintyOptions& o) {
  std::vector<ImagePx> pixels;
  const double stride = std::max(1.0, double(all_pixels.size()) / std::max(1, o.max_pixels));
  for (double i = 0; i < double(all_pixels.size()); i += stride) pixels.push_back(all_pixels[size_t(i)]);
  const auto matches = matchLinePixels(params, pixels, model, 3.0);
  if (matches.size() < 50) return std::nullopt;

  const Eigen::Matrix<double, kParams, 1> x0 = pack(params), h = steps(params);
  auto residual = [&](const CameraParams& p, const LinePixelMatch& m, double& r) {
    double xy[2];
    if (!backProjectPixelLens(p.intrinsics, p.lens, p.rotation, p.position, m.px.u, m.px.v, 0.0, xy)) return false;
    r = model.elements()[m.element].signedDistance(xy) / m.mm_per_px;
    return true;
  };
  // The measurements are the line centres, one per 16 px image cell and
  // model line: the pixels of a cell spread across the painted width and
  // are not independent, their mean is what the fit pins down.
  struct Cell {
    Eigen::Matrix<double, kParams, 1> row = Eigen::Matrix<double, kParams, 1>::Zero();
    double r = 0;
    int n = 0;
  };
  std::map<std::tuple<int, int, int>, Cell> cells;
  CameraParams plus = params, minus = params;
  for (const auto& m : matches) {
    double r0 = 0;
    if (!residual(params, m, r0)) continue;
    Eigen::Matrix<double, kParams, 1> row;
    bool ok = true;
    for (int j = 0; j < kParams && ok; ++j) {
      Eigen::Matrix<double, kParams, 1> xp = x0, xm = x0;
      xp[j] += h[j], xm[j] -= h[j];
      unpack(xp, plus), unpack(xm, minus);
      double rp = 0, rm = 0;
      ok = residual(plus, m, rp) && residual(minus, m, rm);
      row[j] = (rp - rm) / (2 * h[j]);
    }
    if (!ok) continue;
    Cell& c = cells[{m.element, int(m.px.u / 16), int(m.px.v / 16)}];
    c.row += row, c.r += r0, ++c.n;
  }
  std::vector<double> res;
  std::vector<Eigen::Matrix<double, kParams, 1>> rows;
  for (auto& [key, c] : cells) {
    if (c.n < 3) continue;
    res.push_back(std::abs(c.r / c.n));
    rows.push_back(c.row / c.n);
  }
  if (rows.size() < 20) return std::nullopt;
  // Noise of a line centre from the spread of the cells' mean residuals,
  // at least 0.05 px.
  std::nth_element(res.begin(), res.begin() + res.size() / 2, res.end());
  const double sigma = std::max(0.05, 1.4826 * res[res.size() / 2]);
  Eigen::Matrix<double, kParams, kParams> info = Eigen::Matrix<double, kParams, kParams>::Zero();
  for (const auto& row : rows) info += row * row.transpose() / (sigma * sigma);
  if (o.principal_point_sigma_px > 0) {
    const double pp_w = 1 / (o.principal_point_sigma_px * o.principal_point_sigma_px);
    info(1, 1) += pp_w, info(2, 2) += pp_w;
  }
  if (o.height_fixed) info(9, 9) += 1e12;
  // Scale to unit diagonal before inverting: the parameters differ by
  // orders of magnitude.
  Eigen::Matrix<double, kParams, 1> d = info.diagonal().cwiseMax(1e-30).cwiseSqrt().cwiseInverse();
  const Eigen::Matrix<double, kParams, kParams> scaled = d.asDiagonal() * info * d.asDiagonal();
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, kParams, kParams>> eig(scaled);
  const auto ev = eig.eigenvalues();
  Eigen::Matrix<double, kParams, 1> inv_ev;
  for (int i = 0; i < kParams; ++i) inv_ev[i] = ev[i] > 1e-12 * ev.maxCoeff() ? 1 / ev[i] : 1e12;
  const Eigen::Matrix<double, kParams, kParams> cov =
      d.asDiagonal() * eig.eigenvectors() * inv_ev.asDiagonal() * eig.eigenvectors().transpose() * d.asDiagonal();

  // Field positions of a grid of pixels and their spread.
  PredictedFieldError out;
  out.noise_px = sigma;
  out.pixels_used = int(rows.size());
  for (const double z : {0.0, 150.0}) {
    double sum = 0;
    int n = 0;
    for (int gv = 0; gv < 12; ++gv)
      for (int gu = 0; gu < 12; ++gu) {
        const double u = (gu + 0.5) * o.width / 12.0, v = (gv + 0.5) * o.height / 12.0;
        double xy[2];
        if (!backProjectPixelLens(params.intrinsics, params.lens, params.rotation, params.position, u, v, z, xy)) continue;
        if (!area.contains({xy[0], xy[1]})) continue;
        Eigen::Matrix<double, 2, kParams> g;
        bool ok = true;
        for (int j = 0; j < kParams && ok; ++j) {
          Eigen::Matrix<double, kParams, 1> xp = x0, xm = x0;
          xp[j] += h[j], xm[j] -= h[j];
          unpack(xp, plus), unpack(xm, minus);
          double a[2], b[2];
          ok = backProjectPixelLens(plus.intrinsics, plus.lens, plus.rotation, plus.position, u, v, z, a) &&
               backProjectPixelLens(minus.intrinsics, minus.lens, minus.rotation, minus.position, u, v, z, b);
          g(0, j) = (a[0] - b[0]) / (2 * h[j]), g(1, j) = (a[1] - b[1]) / (2 * h[j]);
        }
        if (!ok) continue;
        sum += std::sqrt(std::max(0.0, (g * cov * g.transpose()).trace()));
        ++n;
      }
    (z == 0 ? out.at_carpet_mm : out.at_150_mm) = n ? sum / n : 0;
  }
  return out;
}

}  // namespace dv
