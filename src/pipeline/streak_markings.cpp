#include "pipeline/streak_markings.h"

#include <algorithm>
#include <limits>

#include "pipeline/bayer_subsample.h"
#include "pipeline/score_windows.h"
#include "pipeline/streak_windows.h"

namespace dv {

MarkingMask::MarkingMask(const CameraModel& camera, const FieldModel& field, const RectifiedGrid& grid,
                         double plane_height)
    : camera_(camera),
      plane_height_(plane_height),
      width_(grid.width),
      height_(grid.height),
      cells_(static_cast<size_t>(grid.width) * grid.height, 0) {
  const double step = grid.scale / 2;  // mm along a marking
  auto onPlane = [&](double x, double y) -> std::optional<FieldPoint> {
    const auto px = camera.fieldToImage({x, y, 0});
    return px ? camera.imageToField(*px, plane_height) : std::nullopt;
  };
  auto mark = [&](double x, double y, double thickness, uint16_t index) {
    const double reach = (thickness / 2 + kStreakCellMm) / grid.scale;  // grid cells
    const int r = static_cast<int>(std::ceil(reach));
    const auto p = onPlane(x, y);
    if (!p) return;
    const GridPx g = grid.toGrid({p->x, p->y});
    const int cx = static_cast<int>(std::lround(g.x)), cy = static_cast<int>(std::lround(g.y));
    for (int y = std::max(0, cy - r); y <= std::min(height_ - 1, cy + r); ++y)
      for (int x = std::max(0, cx - r); x <= std::min(width_ - 1, cx + r); ++x) {
        if (std::hypot(x - g.x, y - g.y) > reach) continue;
        uint16_t& c = cells_[static_cast<size_t>(y) * width_ + x];
        if (c == 0) c = index;
        else if ((c & kIndexBits) != index) c |= kCrossingBit;
      }
  };
  for (const FieldLine& l : field.lines) {
    const double len = std::hypot(l.p2.x - l.p1.x, l.p2.y - l.p1.y);
    PlaneMarking m;
    if (len > 0) m.dir = {(l.p2.x - l.p1.x) / len, (l.p2.y - l.p1.y) / len};
    markings_.push_back(m);
    const int n = std::max(1, static_cast<int>(std::ceil(len / step)));
    for (int i = 0; i <= n; ++i)
      mark(l.p1.x + (l.p2.x - l.p1.x) * i / n, l.p1.y + (l.p2.y - l.p1.y) * i / n, l.thickness,
           static_cast<uint16_t>(markings_.size()));
  }
  for (const FieldArc& a : field.arcs) {
    PlaneMarking m;
    m.arc = true;
    const auto c = onPlane(a.center.x, a.center.y);
    m.center = c ? FieldMm{c->x, c->y} : a.center;
    markings_.push_back(m);
    const int n = std::max(1, static_cast<int>(std::ceil(a.span() * a.radius / step)));
    for (int i = 0; i <= n; ++i) {
      const double t = a.a1 + a.span() * i / n;
      mark(a.center.x + a.radius * std::cos(t), a.center.y + a.radius * std::sin(t), a.thickness,
           static_cast<uint16_t>(markings_.size()));
    }
  }
}

bool MarkingMask::discRgb(const cv::Mat& raw, BayerPattern bayer, FieldMm p, float rgb[3]) const {
  const auto c = camera_->fieldToImage({p.x, p.y, plane_height_});
  const auto ex = camera_->fieldToImage({p.x + kColorRadiusMm, p.y, plane_height_});
  const auto ey = camera_->fieldToImage({p.x, p.y + kColorRadiusMm, plane_height_});
  if (!c || !ex || !ey || c->u < 0 || c->v < 0 || c->u > raw.cols - 1 || c->v > raw.rows - 1) return false;
  double radius = 0.5 * (std::hypot(ex->u - c->u, ex->v - c->v) + std::hypot(ey->u - c->u, ey->v - c->v));
  // In samples: 2 x 2 cells of a mosaic (sampleRgbAt), pixels of a color image.
  const bool mosaic = bayer != BayerPattern::None && raw.channels() == 1;
  const double s = mosaic ? 2 : 1, cu = (c->u - (s - 1) / 2) / s, cv = (c->v - (s - 1) / 2) / s;
  // Gaussian weights: the mean moves smoothly with the center, so a thin
  // line's share of it does not jump with its phase on the sample lattice.
  const double sigma = std::max(1.0, radius / s / 1.5), reach = 2.5 * sigma;
  const int cols = raw.cols / static_cast<int>(s), rows = raw.rows / static_cast<int>(s);
  const int i0 = std::max(0, static_cast<int>(std::ceil(cu - reach)));
  const int i1 = std::min(cols - 1, static_cast<int>(std::floor(cu + reach)));
  const int j0 = std::max(0, static_cast<int>(std::ceil(cv - reach)));
  const int j1 = std::min(rows - 1, static_cast<int>(std::floor(cv + reach)));
  constexpr int kMaxTaps = 64;  // per axis: a color disc up to 19 samples in radius
  if (i1 - i0 >= kMaxTaps || j1 - j0 >= kMaxTaps) return false;
  double wx[kMaxTaps];  // separable weights
  for (int i = i0; i <= i1; ++i) wx[i - i0] = std::exp(-(i - cu) * (i - cu) / (2 * sigma * sigma));
  double sum[3] = {0, 0, 0}, n = 0;
  for (int j = j0; j <= j1; ++j) {
    const double wy = std::exp(-(j - cv) * (j - cv) / (2 * sigma * sigma));
    for (int i = i0; i <= i1; ++i) {
      const double w = wy * wx[i - i0];
      float q[3];
      sampleRgbAt(raw, bayer, i, j, q);
      for (int k = 0; k < 3; ++k) sum[k] += w * q[k];
      n += w;
    }
  }
  if (!(n > 0)) return false;
  for (int k = 0; k < 3; ++k) rgb[k] = static_cast<float>(sum[k] / n);
  return true;
}

std::optional<float> MarkingMask::contrastToMarking(const cv::Mat& raw, BayerPattern bayer,
                                                    const BlobColorGate& colors, FieldMm p, int marking) const {
  if (!camera_ || marking < 0 || marking >= static_cast<int>(markings_.size()) || raw.empty()) return std::nullopt;
  float here[3];
  if (!discRgb(raw, bayer, p, here)) return std::nullopt;
  const PlaneMarking& m = markings_[static_cast<size_t>(marking)];
  auto along = [&](double step, FieldMm& q) {
    if (!m.arc) {
      q = {p.x + step * m.dir.x, p.y + step * m.dir.y};
      return true;
    }
    // Along the circle through p about the arc's center.
    const double dx = p.x - m.center.x, dy = p.y - m.center.y, r = std::hypot(dx, dy);
    if (!(r > 0)) return false;
    const double ct = std::cos(step / r), st = std::sin(step / r);
    q = {m.center.x + ct * dx - st * dy, m.center.y + st * dx + ct * dy};
    return true;
  };
  float there[2][3];
  bool seen[2];
  float nearer = std::numeric_limits<float>::max();
  for (int k = 0; k < 2; ++k) {
    FieldMm q;
    seen[k] = along((k == 0 ? -1 : 1) * kMarkingLookMm, q) && discRgb(raw, bayer, q, there[k]);
    if (seen[k]) nearer = std::min(nearer, colors.chromaDistance2(here, there[k]));
  }
  if (!seen[0] && !seen[1]) return std::nullopt;
  // A thin line drifts across the mosaic's phase along it, so its false
  // color comes in stretches: the stretch in the candidate's phase may lie
  // beyond the nearest two (a touch line under tungsten at 1224 x 1024 made
  // orange and cyan stretches of about 100 mm each). The nearest look like
  // it within kMarkingSpanMm either way stands for the marking.
  for (double d = kMarkingLookMm + kMarkingSpanStepMm; d <= kMarkingSpanMm; d += kMarkingSpanStepMm)
    for (double sign : {-1.0, 1.0}) {
      FieldMm q;
      float rgb[3];
      if (along(sign * d, q) && discRgb(raw, bayer, q, rgb))
        nearer = std::min(nearer, colors.chromaDistance2(here, rgb));
    }
  // Beyond the marking's own change along it (the light varies, the
  // phase drifts): a stretch between two others differs from each by less
  // than they differ from each other. Where the image ends on one side
  // that change is unknown, and the marking as far as the image shows it
  // is the reference (a touch line's stretch 22 px from the image's edge,
  // under tungsten, had been left to the fixed floor and passed).
  return seen[0] && seen[1] ? nearer - colors.chromaDistance2(there[0], there[1]) : nearer;
}

}  // namespace dv
