#include "geometry/calibration/image_lines.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

#include "core/units.h"

namespace dv {

std::optional<ImageLine> fitImageLine(const LineGroup& g, const PixelDistortion& d) {
  if (g.pixels.size() < 20) return std::nullopt;
  std::vector<cv::Point2d> pts;
  for (const auto& p : g.pixels) {
    const ImagePx u = d.undistort(p);
    pts.emplace_back(u.u, u.v);
  }
  cv::Vec4d l;
  cv::fitLine(pts, l, cv::DIST_HUBER, 0, 0.01, 0.01);
  ImageLine out;
  out.theta = std::atan2(l[0], -l[1]);  // normal of direction (l0, l1)
  const double nx = std::cos(out.theta), ny = std::sin(out.theta);
  out.rho = nx * l[2] + ny * l[3];
  double sq = 0, tmin = 1e300, tmax = -1e300;
  for (const auto& p : pts) {
    const double r = nx * p.x + ny * p.y - out.rho;
    sq += r * r;
    const double t = -ny * p.x + nx * p.y;
    tmin = std::min(tmin, t), tmax = std::max(tmax, t);
  }
  if (std::sqrt(sq / pts.size()) > 2.0) return std::nullopt;
  out.extent = tmax - tmin;
  out.mid = cv::Point2d(l[2], l[3]);
  return out;
}

double directionDifference(const ImageLine& a, const ImageLine& b) {
  const double d = std::fmod(std::abs(a.theta - b.theta), kPi);
  return std::min(d, kPi - d);
}

std::optional<cv::Point2d> intersect(const ImageLine& a, const ImageLine& b) {
  const double a1 = std::cos(a.theta), b1 = std::sin(a.theta), a2 = std::cos(b.theta), b2 = std::sin(b.theta);
  const double det = a1 * b2 - a2 * b1;
  if (std::abs(det) < 1e-6) return std::nullopt;
  return cv::Point2d((a.rho * b2 - b.rho * b1) / det, (a1 * b.rho - a2 * a.rho) / det);
}

double signedArea(const std::vector<cv::Point2d>& q) {
  double s = 0;
  for (size_t i = 0; i < q.size(); ++i) {
    const auto& a = q[i];
    const auto& b = q[(i + 1) % q.size()];
    s += a.x * b.y - b.x * a.y;
  }
  return s / 2;
}

}  // namespace dv
