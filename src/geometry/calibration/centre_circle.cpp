#include "geometry/calibration/centre_circle.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <spdlog/spdlog.h>

namespace dv {

namespace {

// Ellipse quadric (p - c)^T M (p - c) = 1.
struct Quadric {
  cv::Matx22d m;
  cv::Point2d c;
  explicit Quadric(const ImageEllipse& e) : c(e.center) {
    const double ca = std::cos(e.angle), sa = std::sin(e.angle);
    const cv::Matx22d r(ca, -sa, sa, ca);
    m = r * cv::Matx22d(1 / (e.a * e.a), 0, 0, 1 / (e.b * e.b)) * r.t();
  }
  double value(cv::Point2d p) const {
    const cv::Vec2d d(p.x - c.x, p.y - c.y);
    return (d.t() * m * d)[0];
  }
  // Crossings with the line p0 + t dir.
  std::vector<cv::Point2d> crossings(cv::Point2d p0, cv::Point2d dir) const {
    const cv::Vec2d q(p0.x - c.x, p0.y - c.y), d(dir.x, dir.y);
    const double A = (d.t() * m * d)[0], B = 2 * (q.t() * m * d)[0], C = (q.t() * m * q)[0] - 1;
    const double disc = B * B - 4 * A * C;
    if (!(disc > 0) || A <= 0) return {};
    const double s = std::sqrt(disc);
    return {p0 + dir * ((-B - s) / (2 * A)), p0 + dir * ((-B + s) / (2 * A))};
  }
  // Tangent line at p on the ellipse, homogeneous.
  cv::Vec3d tangent(cv::Point2d p) const {
    const cv::Vec2d g = m * cv::Vec2d(p.x - c.x, p.y - c.y);
    return {g[0], g[1], -(g[0] * p.x + g[1] * p.y)};
  }
};

// Share of the ellipse's parameter angle covered by the points (of 16 bins)
// and share of the points within `tol_px` of it.
void ellipseSupport(const ImageEllipse& e, const std::vector<cv::Point2f>& pts, double tol_px, double& coverage,
                    double& inliers) {
  const double ca = std::cos(e.angle), sa = std::sin(e.angle);
  bool bins[16] = {};
  int in = 0;
  for (const auto& p : pts) {
    const double dx = p.x - e.center.x, dy = p.y - e.center.y;
    const double x = (ca * dx + sa * dy) / e.a, y = (-sa * dx + ca * dy) / e.b;
    const double r = std::hypot(x, y);
    if (std::abs(r - 1) * e.b > tol_px) continue;
    ++in;
    bins[int((std::atan2(y, x) + kPi) / (2 * kPi) * 16) & 15] = true;
  }
  coverage = double(std::count(bins, bins + 16, true)) / 16;
  inliers = pts.empty() ? 0 : double(in) / pts.size();
}

}  // namespace

std::optional<ImageEllipse> findCentreCircle(const LineObservation& obs, const PixelDistortion& dist,
                                             const std::vector<ImageLine>& straight, int width, int height) {
  // Line pixels that no straight line explains, in undistorted pixels.
  const double band = obs.half_width_px + 3.0;
  cv::Mat curved = cv::Mat::zeros(height, width, CV_8U);
  for (const auto& px : obs.pixels) {
    const ImagePx u = dist.undistort(px);
    const cv::Point2d p(u.u, u.v);
    bool on_line = false;
    for (const auto& l : straight)
      if (l.distanceTo(p) < band) on_line = true;
    const int x = int(std::lround(u.u)), y = int(std::lround(u.v));
    if (!on_line && x >= 0 && y >= 0 && x < width && y < height) curved.at<uint8_t>(y, x) = 255;
  }
  // The thinned pixels are a few px apart: join them into arcs.
  cv::dilate(curved, curved, cv::getStructuringElement(cv::MORPH_ELLIPSE, {7, 7}));
  cv::Mat labels, stats, centroids;
  const int n = cv::connectedComponentsWithStats(curved, labels, stats, centroids, 8, CV_32S);
  std::vector<int> comps;
  for (int i = 1; i < n; ++i)
    if (std::max(stats.at<int>(i, cv::CC_STAT_WIDTH), stats.at<int>(i, cv::CC_STAT_HEIGHT)) >= 30) comps.push_back(i);
  std::sort(comps.begin(), comps.end(),
            [&](int a, int b) { return stats.at<int>(a, cv::CC_STAT_AREA) > stats.at<int>(b, cv::CC_STAT_AREA); });
  spdlog::debug("curved components: {} of {}", comps.size(), n - 1);
  if (comps.size() > 6) comps.resize(6);
  std::vector<std::vector<cv::Point2f>> comp_pts(comps.size());
  for (const auto& px : obs.pixels) {
    const ImagePx u = dist.undistort(px);
    const int x = int(std::lround(u.u)), y = int(std::lround(u.v));
    if (x < 0 || y < 0 || x >= width || y >= height) continue;
    const int label = labels.at<int>(y, x);
    for (size_t k = 0; k < comps.size(); ++k)
      if (comps[k] == label) comp_pts[k].emplace_back(float(u.u), float(u.v));
  }
  // The halfway and centre lines cut the circle into up to four arcs: try
  // every set of the largest arcs.
  std::optional<ImageEllipse> best;
  double best_score = 0;
  for (unsigned set = 1; set < (1u << comps.size()); ++set) {
      std::vector<cv::Point2f> pts;
      for (size_t k = 0; k < comps.size(); ++k)
        if (set & (1u << k)) pts.insert(pts.end(), comp_pts[k].begin(), comp_pts[k].end());
      if (pts.size() < 30) continue;
      const cv::RotatedRect r = cv::fitEllipseAMS(pts);
      ImageEllipse e;
      e.center = r.center;
      e.a = r.size.width / 2, e.b = r.size.height / 2, e.angle = r.angle * kPi / 180;
      if (e.b > e.a) std::swap(e.a, e.b), e.angle += kPi / 2;
      if (!(e.b >= 15) || e.a > std::max(width, height) || e.b < 0.25 * e.a) continue;
      double coverage, inliers;
      // The pixels fill the painted line's width.
      ellipseSupport(e, pts, obs.half_width_px + 1.5, coverage, inliers);
      if (coverage < 0.6 || inliers < 0.85) continue;
      e.pixels = int(pts.size());
      const double s = coverage * double(pts.size());
      if (s > best_score) best_score = s, best = e;
    }
  return best;
}

std::vector<std::vector<PointCorrespondence>> centreCircleHypotheses(const ImageEllipse& e,
                                                                     const std::vector<ImageLine>& straight,
                                                                     const PixelDistortion& dist, double R) {
  std::vector<std::vector<PointCorrespondence>> out;
  const Quadric q(e);
  for (const auto& l : straight) {
    // The halfway line passes through the circle's middle.
    if (l.distanceTo(e.center) > 0.3 * e.b) continue;
    const cv::Point2d n(std::cos(l.theta), std::sin(l.theta)), dir(-n.y, n.x);
    const auto ps = q.crossings(n * l.rho, dir);
    if (ps.size() != 2) continue;
    // Tangents at the crossings meet in the vanishing point of the field's
    // x direction (they are the lines y = +-R).
    const cv::Vec3d vx = q.tangent(ps[0]).cross(q.tangent(ps[1]));
    for (int step = -12; step <= 12; ++step) {
      const double s = 0.5 + 0.005 * step;
      const cv::Point2d cs = ps[0] + (ps[1] - ps[0]) * s;  // the circle centre's image
      // Line through cs towards vx: the field line y = 0.
      cv::Point2d d2 = std::abs(vx[2]) > 1e-9 * (std::abs(vx[0]) + std::abs(vx[1]))
                           ? cv::Point2d(vx[0] / vx[2], vx[1] / vx[2]) - cs
                           : cv::Point2d(vx[0], vx[1]);
      const double len = std::hypot(d2.x, d2.y);
      if (!(len > 1e-9)) continue;
      const auto qs = q.crossings(cs, d2 / len);
      if (qs.size() != 2) continue;
      // ps -> (0, +-R), qs -> (+-R, 0); the orientation (field y up, image v
      // down) picks the signs up to the half turn, which is settled later.
      const std::vector<cv::Point2d> img = {ps[0], qs[0], ps[1], qs[1]};
      for (const double sy : {1.0, -1.0}) {
        const std::vector<cv::Point2d> fld = {{0, sy * R}, {R, 0}, {0, -sy * R}, {-R, 0}};
        if (signedArea(fld) * signedArea(img) >= 0) continue;
        std::vector<PointCorrespondence> h;
        for (int c = 0; c < 4; ++c) {
          const auto px = dist.distort({img[c].x, img[c].y});
          if (!px) break;
          h.push_back({{fld[c].x, fld[c].y, 0}, *px});
        }
        if (h.size() == 4) out.push_back(std::move(h));
      }
    }
  }
  return out;
}

}  // namespace dv
