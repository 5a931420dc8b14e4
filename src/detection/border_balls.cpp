#include "detection/border_balls.h"

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

namespace dv {
namespace {

// Probes lie this many ball radii inside the edge and apart along it, in
// kProbeRows rows a radius apart: a ball with its center anywhere from the
// edge to four radii inside covers the nearest probe's sample point, at
// most 0.64 radii from its center. (The blob score's windows reach about
// three radii beyond a ball: a whole ball three radii from the side
// view's edge made no blob in any search.)
constexpr double kProbeInset = 0.5, kProbeStep = 0.8;
constexpr int kProbeRows = 4;
// A run of more probes than a ball's chord can cover (2 radii: 3 probes,
// one more for blur) is no ball.
constexpr int kMaxRunProbes = 4;
// The window: this many radii beyond the run's probes along the edge, and
// as deep as the far rim of a ball covering the row's probes (two radii
// beyond them) and a sample more.
constexpr double kWindowSides = 1.5;
// Lattice spacing in radii (at least kMinStep px).
constexpr double kStepRadii = 0.2, kMinStep = 0.5;
// A ball whose samples fill this share of its disc is whole.
constexpr double kWholeShare = 0.97;

// Area of the part of a disc of radius r inside the half plane s >= 0, its
// center at depth d (d < 0: outside).
double segmentArea(double r, double d) {
  d = std::clamp(d, -r, r);
  return r * r * std::acos(-d / r) + d * std::sqrt(r * r - d * d);
}

}  // namespace

double ballRadiusPx(const CameraModel& camera, const FieldPoint& p, double radius) {
  const auto c = camera.fieldToImage(p);
  if (!c) return 0;
  const Eigen::Vector3d center(p.x, p.y, p.z);
  const Eigen::Vector3d ray = (center - camera.position()).normalized();
  Eigen::Vector3d a = ray.cross(Eigen::Vector3d::UnitZ());
  if (a.norm() < 1e-6) a = Eigen::Vector3d::UnitX();
  a.normalize();
  const Eigen::Vector3d b = ray.cross(a).normalized();
  double sum = 0;
  int n = 0;
  for (const Eigen::Vector3d& e : {a, Eigen::Vector3d(-a), b, Eigen::Vector3d(-b)}) {
    const Eigen::Vector3d q = center + radius * e;
    if (const auto px = camera.fieldToImage({q.x(), q.y(), q.z()})) {
      sum += std::hypot(px->u - c->u, px->v - c->v);
      ++n;
    }
  }
  return n ? sum / n : 0;
}

BorderBallFinder::BorderBallFinder(const CameraModel& camera, const FieldRect& area, double ball_radius)
    : camera_(camera), ball_radius_(ball_radius) {
  width_ = camera.calibration().image_width;
  height_ = camera.calibration().image_height;
  if (width_ <= 0 || height_ <= 0) return;
  for (int e = 0; e < 4; ++e)
    for (int row = 0; row < kProbeRows; ++row) {
      const double len = edgeLength(e);
      double t = 0;
      while (t <= len) {
        double step = 2;  // px, where no ball lies
        if (const auto p = camera.imageToField(edgePoint(e, t, 0), ball_radius); p && area.contains({p->x, p->y})) {
          const double r = ballRadiusPx(camera, *p, ball_radius);
          if (r >= 1) {
            probes_.push_back({e, t, r, row, edgePoint(e, t, (kProbeInset + row) * r)});
            step = std::max(1.0, kProbeStep * r);
          }
        }
        t += step;
      }
    }
  hit_.resize(probes_.size());
  samples_.reserve(4096);
}

double BorderBallFinder::edgeLength(int edge) const { return edge < 2 ? height_ : width_; }

ImagePx BorderBallFinder::edgePoint(int edge, double t, double s) const {
  // The image covers [-0.5, size - 0.5] (pixel centers at integers).
  switch (edge) {
    case 0: return {-0.5 + s, t - 0.5};
    case 1: return {width_ - 0.5 - s, t - 0.5};
    case 2: return {t - 0.5, -0.5 + s};
    default: return {t - 0.5, height_ - 0.5 - s};
  }
}

void BorderBallFinder::find(const FrameView& frame, const BallColorTest& test, std::vector<BorderBall>& out) {
  if (!frame.image || frame.image->empty() || probes_.empty()) return;
  if (frame.image->cols != width_ || frame.image->rows != height_) return;
  for (size_t i = 0; i < probes_.size(); ++i) {
    float rgb[3];
    frameRgbAt(frame, probes_[i].at.u, probes_[i].at.v, rgb);
    hit_[i] = test.isBall(rgb);
  }
  const int n = static_cast<int>(probes_.size());
  const size_t first = out.size();
  for (int i = 0; i < n;) {
    if (!hit_[i]) {
      ++i;
      continue;
    }
    int j = i;
    while (j + 1 < n && hit_[j + 1] && probes_[j + 1].edge == probes_[i].edge && probes_[j + 1].row == probes_[i].row)
      ++j;
    BorderBall b;
    // A ball two rows see is one ball.
    auto seen = [&] {
      for (size_t k = first; k < out.size(); ++k)
        if (std::hypot(out[k].center.u - b.center.u, out[k].center.v - b.center.v) < probes_[i].radius) return true;
      return false;
    };
    if (j - i + 1 <= kMaxRunProbes && fit(frame, test, i, j, b) && !seen()) out.push_back(b);
    i = j + 1;
  }
}

bool BorderBallFinder::fit(const FrameView& frame, const BallColorTest& test, int first, int last,
                           BorderBall& ball) {
  const Probe& a = probes_[first];
  const Probe& z = probes_[last];
  const int edge = a.edge;
  double r = 0;
  for (int i = first; i <= last; ++i) r += probes_[i].radius;
  r /= last - first + 1;
  const double t0 = a.t - kWindowSides * r, t1 = z.t + kWindowSides * r;
  // A window across a corner would need the other edge's cut as well.
  if (t0 < 0 || t1 > edgeLength(edge)) return false;
  const double h = std::max(kMinStep, kStepRadii * r);
  const double depth = (kProbeInset + a.row + 2) * r + h;
  const int nt = static_cast<int>(std::ceil((t1 - t0) / h)), ns = static_cast<int>(std::ceil(depth / h));
  // The ball-colored samples: their area, centroid, color.
  samples_.clear();
  double sum_t = 0, sum_s = 0, sum_rgb[3] = {0, 0, 0};
  int at_edge = 0;  // ball-colored samples in the row along the edge
  for (int j = 0; j < ns; ++j) {
    const double s = (j + 0.5) * h;
    for (int i = 0; i < nt; ++i) {
      const double t = t0 + (i + 0.5) * h;
      const ImagePx px = edgePoint(edge, t, s);
      Sample smp{t, s, {0, 0, 0}};
      frameRgbAt(frame, px.u, px.v, smp.rgb);
      if (!test.isBall(smp.rgb)) continue;
      // Ball color in the window's last row: something larger than a ball.
      if (j == ns - 1) return false;
      if (samples_.size() == samples_.capacity()) return false;  // no allocation
      samples_.push_back(smp);
      at_edge += j == 0;
      sum_t += t;
      sum_s += s;
      for (int c = 0; c < 3; ++c) sum_rgb[c] += smp.rgb[c];
    }
  }
  if (samples_.empty()) return false;
  const double area = samples_.size() * h * h;
  const double full = kPi * r * r;
  if (area < 0.5 * kMinBorderVisible * full) return false;
  const double tc = sum_t / samples_.size();
  // Cut by the edge (colored right at it, short of a whole disc): the
  // center's depth from the area (segmentArea rises with d). Else whole:
  // the centroid, its disc in the image.
  const bool cut = at_edge > 0 && area < kWholeShare * full;
  double d = sum_s / samples_.size();
  if (cut) {
    double lo = -r, hi = r;
    for (int k = 0; k < 40; ++k) {
      const double mid = 0.5 * (lo + hi);
      (segmentArea(r, mid) < area ? lo : hi) = mid;
    }
    d = 0.5 * (lo + hi);
  } else if (d < r - 1.5 * h) {
    return false;  // as much as a whole ball, yet reaching beyond the edge
  }
  // The fitted disc must reach as deep as the samples do: a whole ball
  // near the edge, short of area only by blur and the lattice, is not cut.
  for (const Sample& smp : samples_)
    if (smp.s > d + r + 1.5 * h) return false;
  const double visible = cut ? segmentArea(r, d) / full : 1.0;
  if (visible < kMinBorderVisible) return false;
  // Overlap of the samples with the fitted disc (in the image), counted on
  // the lattice.
  int inter = 0;
  for (const Sample& smp : samples_) inter += (smp.t - tc) * (smp.t - tc) + (smp.s - d) * (smp.s - d) <= r * r;
  int in_disc = 0;
  for (int j = 0; j < ns; ++j) {
    const double s = (j + 0.5) * h;
    if (std::abs(s - d) > r) continue;
    const double half = std::sqrt(r * r - (s - d) * (s - d));
    for (int i = 0; i < nt; ++i) in_disc += std::abs(t0 + (i + 0.5) * h - tc) <= half;
  }
  const double uni = static_cast<double>(samples_.size()) + in_disc - inter;
  const double overlap = uni > 0 ? inter / uni : 0;
  if (overlap < kMinBorderOverlap) return false;
  ball.center = edgePoint(edge, tc, d);
  const auto p = camera_.imageToField(ball.center, ball_radius_);
  if (!p) return false;
  ball.position = {p->x, p->y, ball_radius_};
  for (int c = 0; c < 3; ++c) ball.rgb[c] = static_cast<float>(sum_rgb[c] / samples_.size());
  ball.overlap = overlap;
  ball.visible = visible;
  ball.whole = !cut;
  return true;
}

}  // namespace dv
