#include "pipeline/blob_color_gate.h"

#include <algorithm>
#include <cmath>

#include "pipeline/bayer_full.h"
#include "pipeline/score_windows.h"

namespace dv {
namespace {

constexpr double kLineStepMm = 25;      // between line samples
constexpr int kMaxLinePoints = 300;     // evenly thinned beyond
constexpr double kImageMarginPx = 3;
constexpr int kSiteReach = 2;
constexpr double kCarpetOffsetMm = 80;  // beside a line, for its contrast
// White lines are this much brighter than the carpet beside them (white on
// the lightest green carpet: 1.9; a line 2 px wide reads about 0.85 of its
// white). Less: no lines in these places (a painted test scene, a field
// other than the geometry), so no white balance is read.
constexpr float kMinLineContrast = 1.4f;  // px around a line sample searched for each channel's site
// Line samples on the lines' center: the brightest share of them (a sample
// beside the center, under a robot or in shadow reads darker).
constexpr double kBrightShare = 0.25;
constexpr int kMinNeutralSamples = 8;
// Of the strong peaks, the share that are most colored sets the frame's
// saturation scale: in a frame with robots these are pattern dots.
constexpr double kScaleQuantile = 0.9;
// A blob must show this share of the frame's scale. Under the shipped
// colors dots show 0.6..0.9 and line crossings 0.1..0.2, the same ratio in
// a frame desaturated to 0.4 (dots 0.25..0.4, crossings below 0.08).
constexpr float kScaleShare = 0.3f;
constexpr int kMaxPeaksForScale = 2048;
// Colored strong peaks needed for a marker contrast: one robot's pattern.
constexpr int kMinMarkersForContrast = 4;
// Lines read this bright in a channel are clipped there. Clipped in two or
// three, their color says nothing of the cast (under tungsten at exposure
// 1.5 and 3:1 uneven light the lit lines read 255, 255, 255 while the
// shaded touch line reads 158, 136, 65, the ball's hue), and the frame's
// colors have no known scale for the fast-ball pass. One clipped channel
// (a cold cast's blue) leaves the other two to tell.
constexpr float kLineClipLevel = 250;

// The kScaleQuantile quantile of v (reordered).
float quantile(std::vector<float>& v) {
  const size_t q = std::min(v.size() - 1, static_cast<size_t>(kScaleQuantile * v.size()));
  std::nth_element(v.begin(), v.begin() + q, v.end());
  return v[q];
}

// The co-sited color of the 2x2 cell under image position p.
void pixelRgb(const cv::Mat& raw, BayerPattern bayer, const ImagePx& p, float rgb[3]) {
  const int u = std::clamp(static_cast<int>(std::lround(p.u)), 0, raw.cols - 1);
  const int v = std::clamp(static_cast<int>(std::lround(p.v)), 0, raw.rows - 1);
  if (bayer == BayerPattern::None || raw.type() == CV_8UC3) {
    const cv::Vec3b q = raw.at<cv::Vec3b>(v, u);
    rgb[0] = q[2], rgb[1] = q[1], rgb[2] = q[0];
  } else {
    fullBayerRgbAt(raw, bayer, u, v, rgb);
  }
}

}  // namespace

BlobColorGate::BlobColorGate(const CameraModel& camera, const FieldModel& field) {
  const int w = camera.calibration().image_width, h = camera.calibration().image_height;
  auto inImage = [&](double x, double y, ImagePx& px) {
    const auto p = camera.fieldToImage({x, y, 0});
    if (!p || p->u < kImageMarginPx || p->v < kImageMarginPx || p->u > w - 1 - kImageMarginPx ||
        p->v > h - 1 - kImageMarginPx)
      return false;
    px = *p;
    return true;
  };
  // A line point and the carpet beside it (nx, ny: unit normal).
  auto add = [&](double x, double y, double nx, double ny) {
    ImagePx line, carpet;
    if (inImage(x, y, line) && inImage(x + kCarpetOffsetMm * nx, y + kCarpetOffsetMm * ny, carpet)) {
      points_.push_back(line);
      carpet_.push_back(carpet);
    }
  };
  int side = 1;  // alternate sides, so that no line's one side decides
  for (const FieldLine& l : field.lines) {
    const double len = std::hypot(l.p2.x - l.p1.x, l.p2.y - l.p1.y);
    if (len <= 0) continue;
    const double nx = -(l.p2.y - l.p1.y) / len, ny = (l.p2.x - l.p1.x) / len;
    const int n = std::max(1, static_cast<int>(len / kLineStepMm));
    for (int i = 0; i <= n; ++i, side = -side)
      add(l.p1.x + (l.p2.x - l.p1.x) * i / n, l.p1.y + (l.p2.y - l.p1.y) * i / n, side * nx, side * ny);
  }
  for (const FieldArc& a : field.arcs) {
    const double span = a.span();
    const int n = std::max(1, static_cast<int>(span * a.radius / kLineStepMm));
    for (int i = 0; i <= n; ++i, side = -side) {
      const double t = a.a1 + span * i / n;
      add(a.center.x + a.radius * std::cos(t), a.center.y + a.radius * std::sin(t), side * std::cos(t),
          side * std::sin(t));
    }
  }
  if (static_cast<int>(points_.size()) > kMaxLinePoints) {
    std::vector<ImagePx> thin, thin_carpet;
    for (int i = 0; i < kMaxLinePoints; ++i) {
      const size_t k = points_.size() * i / kMaxLinePoints;
      thin.push_back(points_[k]);
      thin_carpet.push_back(carpet_[k]);
    }
    points_.swap(thin);
    carpet_.swap(thin_carpet);
  }
  bright_.resize(points_.size());
  order_.resize(points_.size());
  rgb_.resize(3 * points_.size());
  peak_saturation_.reserve(kMaxPeaksForScale);
  peak_contrast_.reserve(kMaxPeaksForScale);
  scratch_.reserve(kMaxPeaksForScale);
  threshold_ = kMinBlobSaturation;
}

void BlobColorGate::measureNeutral(const cv::Mat& raw, BayerPattern bayer) {
  neutral_ = {};
  line_saturation_ = 0;
  carpet_valid_ = false;
  lines_clipped_ = false;
  gain_[0] = gain_[1] = gain_[2] = 1;
  const int n = static_cast<int>(points_.size());
  if (n == 0 || raw.empty()) return;
  const bool bgr = bayer == BayerPattern::None || raw.type() == CV_8UC3;
  // Red site of the 2x2 cell (x, y parity); blue is diagonal to it.
  const int rx = bayer == BayerPattern::GRBG || bayer == BayerPattern::BGGR;
  const int ry = bayer == BayerPattern::GBRG || bayer == BayerPattern::BGGR;
  for (int i = 0; i < n; ++i) {
    float* c = &rgb_[3 * i];
    c[0] = c[1] = c[2] = 0;
    const int u0 = static_cast<int>(std::lround(points_[i].u)), v0 = static_cast<int>(std::lround(points_[i].v));
    // Each channel's brightest site within a pixel of the line's center: a
    // line 2 px wide (1224 x 1024 from 5 m) fills no 2x2 window, but its
    // center sites are white.
    for (int v = std::max(0, v0 - kSiteReach); v <= std::min(raw.rows - 1, v0 + kSiteReach); ++v)
      for (int u = std::max(0, u0 - kSiteReach); u <= std::min(raw.cols - 1, u0 + kSiteReach); ++u) {
        if (bgr) {
          const cv::Vec3b p = raw.at<cv::Vec3b>(v, u);
          c[0] = std::max(c[0], float(p[2])), c[1] = std::max(c[1], float(p[1])), c[2] = std::max(c[2], float(p[0]));
        } else {
          const bool xr = (u & 1) == rx, yr = (v & 1) == ry;
          const int ch = xr && yr ? 0 : (!xr && !yr ? 2 : 1);
          c[ch] = std::max(c[ch], float(raw.at<uint8_t>(v, u)));
        }
      }
    bright_[i] = order_[i] = c[0] + c[1] + c[2];
  }
  const int keep = static_cast<int>(n * kBrightShare);
  if (keep < kMinNeutralSamples) return;
  std::nth_element(order_.begin(), order_.begin() + (n - keep), order_.end());
  const float cut = order_[n - keep];
  // Per channel, the median over the brightest samples (a robot's marker
  // on a line is bright too, but rare).
  for (int k = 0; k < 3; ++k) {
    int m = 0;
    for (int i = 0; i < n; ++i)
      if (bright_[i] >= cut && bright_[i] > 0) order_[m++] = rgb_[3 * i + k];
    if (m < kMinNeutralSamples) return;
    std::nth_element(order_.begin(), order_.begin() + m / 2, order_.begin() + m);
    neutral_.rgb[k] = order_[m / 2];
    neutral_.samples = m;
  }
  lines_clipped_ = (neutral_.rgb[0] >= kLineClipLevel) + (neutral_.rgb[1] >= kLineClipLevel) +
                       (neutral_.rgb[2] >= kLineClipLevel) >= 2;
  const float lo = std::min({neutral_.rgb[0], neutral_.rgb[1], neutral_.rgb[2]});
  if (lo < 1) return;  // a channel missing: no white balance can be read
  // The carpet beside the lines, per channel the median.
  for (int i = 0; i < n; ++i) pixelRgb(raw, bayer, carpet_[i], &rgb_[3 * i]);
  float* carpet = carpet_rgb_;
  for (int k = 0; k < 3; ++k) {
    for (int i = 0; i < n; ++i) order_[i] = rgb_[3 * i + k];
    std::nth_element(order_.begin(), order_.begin() + n / 2, order_.begin() + n);
    carpet[k] = order_[n / 2];
  }
  carpet_valid_ = true;
  if (neutral_.rgb[0] + neutral_.rgb[1] + neutral_.rgb[2] < kMinLineContrast * (carpet[0] + carpet[1] + carpet[2]))
    return;
  neutral_.valid = true;
  for (int k = 0; k < 3; ++k) gain_[k] = neutral_.rgb[1] / neutral_.rgb[k];
  // What a line crossing's blob shows: line and carpet, half and half (a
  // crossing's disc holds more line, so less saturation).
  float mix[3];
  for (int k = 0; k < 3; ++k) mix[k] = 0.5f * (neutral_.rgb[k] + carpet[k]);
  line_saturation_ = saturation(mix);
}

void BlobColorGate::adoptNeutral(const BlobColorGate& other) {
  neutral_ = other.neutral_;
  line_saturation_ = other.line_saturation_;
  carpet_valid_ = other.carpet_valid_;
  lines_clipped_ = other.lines_clipped_;
  for (int k = 0; k < 3; ++k) carpet_rgb_[k] = other.carpet_rgb_[k];
  for (int k = 0; k < 3; ++k) gain_[k] = other.gain_[k];
}

float BlobColorGate::saturation(const float rgb[3]) const {
  const float r = rgb[0] * gain_[0], g = rgb[1] * gain_[1], b = rgb[2] * gain_[2];
  const float hi = std::max({r, g, b}), lo = std::min({r, g, b});
  return (hi - lo) / (hi + 1);
}

void BlobColorGate::addPeak(const float rgb[3]) {
  if (static_cast<int>(peak_saturation_.size()) >= kMaxPeaksForScale) return;
  peak_saturation_.push_back(saturation(rgb));
  peak_contrast_.push_back(chromaDistance2(rgb, carpet_rgb_));
}

float BlobColorGate::chromaDistance2(const float x[3], const float y[3]) const {
  const float d[3] = {x[0] - y[0], x[1] - y[1], x[2] - y[2]};
  const float a = chroma_.a[0] * d[0] + chroma_.a[1] * d[1] + chroma_.a[2] * d[2];
  const float b = chroma_.b[0] * d[0] + chroma_.b[1] * d[1] + chroma_.b[2] * d[2];
  return a * a + b * b;
}

void BlobColorGate::endPeaks() {
  // Without the lines the frame's neutral is unknown: the fixed gate.
  threshold_ = kMinBlobSaturation;
  marker_contrast_ = 0;
  if (peak_saturation_.empty() || !neutral_.valid) return;
  scratch_.assign(peak_saturation_.begin(), peak_saturation_.end());
  threshold_ = std::min(kMinBlobSaturation, std::max(line_saturation_, kScaleShare * quantile(scratch_)));
  // The marker contrast over the peaks that pass the gate (line crossings
  // and gray features would pull it toward the carpet's own texture).
  scratch_.clear();
  for (size_t i = 0; i < peak_saturation_.size(); ++i)
    if (peak_saturation_[i] >= threshold_) scratch_.push_back(peak_contrast_[i]);
  if (carpet_valid_ && !lines_clipped_ && static_cast<int>(scratch_.size()) >= kMinMarkersForContrast)
    marker_contrast_ = quantile(scratch_);
}

}  // namespace dv
