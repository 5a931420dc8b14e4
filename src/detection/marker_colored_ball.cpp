#include "detection/marker_colored_ball.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "detection/clipped_color.h"
#include "detection/frame_blob.h"
#include "geometry/robot_pattern.h"

namespace dv {

using namespace color_class;

namespace {
constexpr int kRingSamples = 24;
// Beyond a robot's top by a side dot's radius (its blurred rim).
constexpr double kBeyondTopMm = RobotPatternGeometry::kTopRadius + RobotPatternGeometry::kSideBlobRadius;
// The ball's color as ever more light clips it: its channels scaled by `t`
// from where the brightest reaches the sensor's top, each capped there. A
// camera clips before its gamma, and a gamma scales every unclipped channel
// alike, so the path is the same under any gamma.
ColorVec clippedBy(const ColorVec& color, float t) {
  const float top = std::max({color.c[0], color.c[1], color.c[2]});
  float rgb[3];
  for (int k = 0; k < 3; ++k) rgb[k] = std::min(255.f, 255.f * t * color.c[k] / top);
  return colorFeature(rgb[0], rgb[1], rgb[2]);
}
// Steps along that path: a tenth more light each, fine beside a class's
// least reach (a step moves a channel's chromaticity by a few units).
constexpr float kClipStep = 1.1f;
}  // namespace

bool MarkerColoredBallTest::isBall(const float rgb[3]) const {
  if (judge_.isBall(rgb)) return true;
  const ClippedColor seen(rgb);
  if (k_ < 0 || seen.saturated()) return false;
  const float d = seen.distance(f_.color[k_]);
  const float reach = classReach(f_.spread[k_]);
  return d <= reach && d < seen.distance(f_.color[kField]) && (!around_ || d < seen.distance(*around_));
}

bool MarkerColoredBallTest::isRim(const float rgb[3]) const {
  const ClippedColor seen(rgb);
  if (seen.saturated()) return false;
  const float reach = classReach(f_.spread[k_ >= 0 ? k_ : kOrange]);
  // The rim mixes the carpet with the marker's color or, with the carpet
  // the ring shows, with the ball's own as the light clips it: from orange
  // through a pale yellow whose blue the cast and gamma set, not the
  // yellow centers' (a sun patch's clipped balls read 20..47 from those and
  // 0.6..7.3 from this path).
  // The path starts from the frame's orange or, where no ball taught it
  // yet, from the reference orange as this camera shows the markers'
  // (ColorMap): a desaturating camera pales the ball's blue up too.
  auto alongClipPath = [&](const ColorVec& carpet, const ColorVec& orange) {
    const float dimmest = std::max(1.f, std::min({orange.c[0], orange.c[1], orange.c[2]}));
    const float last = std::max({orange.c[0], orange.c[1], orange.c[2]}) / dimmest;
    float d = std::numeric_limits<float>::max();
    for (float t = 1; t < last; t *= kClipStep)
      d = std::min(d, streakColorDistance(seen, carpet, clippedBy(orange, t)));
    return d;
  };
  auto mixWith = [&](const ColorVec& carpet, bool clip_path) {
    float d = k_ >= 0 ? streakColorDistance(seen, carpet, f_.color[k_]) : std::numeric_limits<float>::max();
    if (clip_path) d = std::min(d, alongClipPath(carpet, f_.color[kOrange]));
    if (clip_path && f_.mapped_orange) d = std::min(d, alongClipPath(carpet, *f_.mapped_orange));
    return d <= reach && d < seen.distance(carpet);
  };
  return mixWith(f_.color[kField], false) || (around_ && mixWith(*around_, true));
}

namespace {
// The ring's samples that lie in the image, into rgb (kRingSamples x 3);
// their count.
int ringSamples(const FrameView& frame, ImagePx center, double radius_px, double ball_radius_mm, float* rgb,
                double ring_mm = kCarpetRingMm) {
  if (!frame.image || frame.image->empty()) return 0;
  const double w = frame.image->cols, h = frame.image->rows, r = ring_mm / ball_radius_mm * radius_px;
  int n = 0;
  for (int i = 0; i < kRingSamples; ++i) {
    const double a = 2 * kPi * i / kRingSamples;
    const double u = center.u + r * std::cos(a), v = center.v + r * std::sin(a);
    if (u < 0 || v < 0 || u > w - 1 || v > h - 1) continue;
    frameRgbAt(frame, u, v, rgb + 3 * n++);
  }
  return n;
}

// Per-channel median RGB of n ring samples.
void medianRgb(const float* ring, int n, float median[3]) {
  float v[kRingSamples];
  for (int k = 0; k < 3; ++k) {
    for (int i = 0; i < n; ++i) v[i] = ring[3 * i + k];
    std::nth_element(v, v + n / 2, v + n);
    median[k] = v[n / 2];
  }
}
ColorVec medianColor(const float* ring, int n) {
  float median[3];
  medianRgb(ring, n, median);
  return colorFeature(median[0], median[1], median[2]);
}

// The carpet as it lies beyond the top of a robot a blob at `center` would
// be the center of, in the ball's own light (a sun patch's lit carpet):
// that ring's median color, where at least half the ring shows it within a
// color's noise. (Around a side dot of a robot not found, in a sun patch
// at gamma 0.74, the ring crossed its top and a neighbour's: its median
// lay near the tops', 7 of its 24 samples within the noise.)
bool carpetBeyond(const FrameView& frame, ImagePx center, double radius_px, double ball_radius_mm, ColorVec& beyond) {
  float ring[3 * kRingSamples];
  const int n = ringSamples(frame, center, radius_px, ball_radius_mm, ring, kBeyondTopMm);
  if (2 * n < kRingSamples) return false;
  beyond = medianColor(ring, n);
  int alike = 0;
  for (int i = 0; i < n; ++i) alike += ClippedColor(ring + 3 * i).distance(beyond) <= kMinClassRadius;
  return alike >= kMinCarpetAroundBall * kRingSamples;
}
}  // namespace

double ringLikeTheCarpetBeyond(const FrameView& frame, ImagePx center, double radius_px, double ball_radius_mm) {
  ColorVec beyond;
  if (!carpetBeyond(frame, center, radius_px, ball_radius_mm, beyond)) return 0;
  float ring[3 * kRingSamples];
  const int n = ringSamples(frame, center, radius_px, ball_radius_mm, ring);
  int alike = 0;
  for (int i = 0; i < n; ++i) alike += ClippedColor(ring + 3 * i).distance(beyond) <= kMinClassRadius;
  return static_cast<double>(alike) / kRingSamples;
}

double carpetAroundBall(const FrameView& frame, const FrameColors* colors, ImagePx center, double radius_px,
                        double ball_radius_mm, float brightness, int* may_be_top) {
  ColorVec beyond;
  const bool has_beyond = carpetBeyond(frame, center, radius_px, ball_radius_mm, beyond);
  float ring[3 * kRingSamples];
  const int n = ringSamples(frame, center, radius_px, ball_radius_mm, ring);
  int carpet = 0, dark = 0;
  for (int i = 0; i < n; ++i) {
    const float* rgb = ring + 3 * i;
    const ClippedColor seen(rgb);
    // As the carpet beyond, within a color's noise: carpet, however dark
    // beside the ball (a red ball on a dark carpet) or near a class (a cold
    // cast's lit carpet clips to the sky-blue centers' color).
    if (has_beyond && seen.distance(beyond) <= kMinClassRadius) {
      ++carpet;
      continue;
    }
    if (rgb[0] + rgb[1] + rgb[2] < kTopBrightness * brightness) {
      ++dark;
      continue;
    }
    if (!colors) {
      ++carpet;
      continue;
    }
    int nearest = kField;
    for (int k = 0; k < kNumClasses; ++k)
      if (k != kGreen && colors->seen[k] && seen.distance(colors->color[k]) < seen.distance(colors->color[nearest]))
        nearest = k;
    carpet += nearest == kField;
  }
  if (may_be_top) *may_be_top = dark + kRingSamples - n;
  return static_cast<double>(carpet) / kRingSamples;
}

bool rgbAroundBall(const FrameView& frame, ImagePx center, double radius_px, double ball_radius_mm, float rgb[3]) {
  float ring[3 * kRingSamples];
  const int n = ringSamples(frame, center, radius_px, ball_radius_mm, ring);
  if (2 * n < kRingSamples) return false;
  medianRgb(ring, n, rgb);
  return true;
}

bool colorAroundBall(const FrameView& frame, ImagePx center, double radius_px, double ball_radius_mm, ColorVec& color) {
  float rgb[3];
  if (!rgbAroundBall(frame, center, radius_px, ball_radius_mm, rgb)) return false;
  color = colorFeature(rgb[0], rgb[1], rgb[2]);
  return true;
}

}  // namespace dv
