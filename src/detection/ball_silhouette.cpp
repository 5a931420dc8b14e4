#include "detection/ball_silhouette.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "detection/color_classes.h"

namespace dv {
namespace {

inline double sq(double v) { return v * v; }

// The silhouette's centroid is taken over a disc of this many ball radii
// around the current center: wide enough for the blur around a whole ball,
// narrow enough to leave the markers of a robot the ball touches outside.
constexpr double kCentroidRadii = 1.6;
// Samples are judged once, on a lattice over the disc around the start
// that holds every centroid disc within half a radius of it.
constexpr double kReachRadii = 0.5;
// Lattice spacing in ball radii: about 200 samples, whatever the ball's
// size in the image (the color test is most of the cost).
constexpr double kStepRadii = 0.25;
// A whole ball's silhouette covers its disc, blurred by a pixel or so.
constexpr double kMinAreaShare = 0.6, kMaxAreaShare = 1.5;
constexpr int kPasses = 4;
// A ball alone: its silhouette ends at its rim plus the blur. Ball-colored
// samples beyond kRimRadii covering more than kMaxBeyondRim of its disc
// are something else merged with it (a wall, a marker, a second ball).
constexpr double kRimRadii = 1.25, kMaxBeyondRim = 0.1;
// The ball's core color is read within kCoreRadii of the yes/no center,
// the carpet's beyond kCarpetRadii (past rim and blur); a sample farther
// than kMaxOffMix times the core-to-carpet distance from their mixing line
// is something else.
constexpr double kCoreRadii = 0.6, kCarpetRadii = 1.5;
constexpr float kMaxOffMix = 0.35f;
// Carpet-colored samples stand for the background where they are at least
// 1 / kMinCarpetShare of what lies beyond kCarpetRadii.
constexpr int kMinCarpetShare = 4;
constexpr int kMaxSide = 2 * static_cast<int>((kCentroidRadii + kReachRadii) / kStepRadii) + 3;

// Chromaticity without colorFeature's dark floor, which pulls a dark color
// toward black: the shaded underside would weigh less than the lit cap.
ColorVec pureChromaticity(const float rgb[3]) {
  const float k = 300.f / std::max(rgb[0] + rgb[1] + rgb[2], 1.f);
  return {{rgb[0] * k, rgb[1] * k, rgb[2] * k}};
}

// The ball's color test says yes or no, and a shaded rim (the ball's
// underside, seen from the side, over its own shadow) says no where a lit
// rim's samples of the same coverage say yes: the yes/no centroid leans
// to the lit side, a few tenths of a pixel, which at a grazing view are
// millimetres along it. Each sample's share of ball instead, from where
// its chromaticity (which shading leaves) lies between the ball's core and
// the carpet around it (carpet-colored samples, not a line or wall beside
// the ball, where enough are), weighs blur on both rims alike. A sample
// that is no mix of the two weighs nothing (a marker nearby), or all where
// the test says it is the ball's (a ball clipped in its lit cap: its
// unclipped shaded side lies off the mix of the cap with the carpet, and
// left out it pulled the center 3 mm to the light at 2448 x 2048). (cu, cv)
// in: the yes/no centroid; out: the weighted one, unless core or carpet is
// missing.
void softCentroid(const float* du, const float* dv, const ColorVec* color, const uint8_t* is_ball,
                  const uint8_t* is_carpet, int n, double r, double& cu, double& cv) {
  ColorVec core, carpet, around;
  int n_core = 0, n_carpet = 0, n_around = 0;
  auto add = [](ColorVec& sum, const ColorVec& c) {
    for (int i = 0; i < 3; ++i) sum.c[i] += c.c[i];
  };
  for (int k = 0; k < n; ++k) {
    const double d2 = sq(du[k] - cu) + sq(dv[k] - cv);
    if (is_ball[k] && d2 <= sq(kCoreRadii * r)) add(core, color[k]), ++n_core;
    if (is_ball[k] || d2 < sq(kCarpetRadii * r)) continue;
    add(around, color[k]), ++n_around;
    if (is_carpet[k]) add(carpet, color[k]), ++n_carpet;
  }
  // A ball in a sun patch lies on carpet the frame's class does not reach:
  // all that surrounds it is its background there.
  if (n_carpet * kMinCarpetShare < n_around) carpet = around, n_carpet = n_around;
  if (n_core == 0 || n_carpet == 0) return;
  float axis[3], len2 = 0;
  for (int i = 0; i < 3; ++i) {
    core.c[i] /= n_core, carpet.c[i] /= n_carpet;
    axis[i] = core.c[i] - carpet.c[i];
    len2 += axis[i] * axis[i];
  }
  if (len2 <= 0) return;
  const double window = kCentroidRadii * r;
  for (int pass = 0; pass < kPasses; ++pass) {
    double su = 0, sv = 0, sw = 0;
    for (int k = 0; k < n; ++k) {
      if (sq(du[k] - cu) + sq(dv[k] - cv) > sq(window)) continue;
      float along = 0, off2 = 0;
      for (int i = 0; i < 3; ++i) along += (color[k].c[i] - carpet.c[i]) * axis[i];
      float a = std::clamp(along / len2, 0.f, 1.f);
      for (int i = 0; i < 3; ++i) off2 += sq(color[k].c[i] - carpet.c[i] - a * axis[i]);
      if (off2 > sq(kMaxOffMix) * len2) {
        if (!is_ball[k]) continue;
        a = 1;
      }
      su += a * du[k], sv += a * dv[k], sw += a;
    }
    if (sw <= 0) return;
    const double nu = su / sw, nv = sv / sw, moved = std::hypot(nu - cu, nv - cv);
    cu = nu, cv = nv;
    if (moved < 0.01 * r) break;
  }
}

// The centroid of the ball-colored samples near `origin`, whose lattice is
// judged once; false where the silhouette is no whole ball alone. (cu, cv):
// the center from the origin (px).
// `beyond`, where given: the share of the disc that ball-colored samples
// cover beyond the rim around the yes/no centroid, whatever the area.
bool settle(const FrameView& frame, const BallColorTest& test, ImagePx origin, double r, double& cu, double& cv,
            double* beyond_share = nullptr) {
  const double step = kStepRadii * r;
  const double reach = (kCentroidRadii + kReachRadii) * r;
  const int half = std::min(static_cast<int>(std::ceil(reach / step)), (kMaxSide - 1) / 2);
  // The whole lattice inside the image: a ball at the border is the border
  // finder's.
  const double w = frame.image->cols, h = frame.image->rows;
  if (origin.u - reach < 0 || origin.v - reach < 0 || origin.u + reach > w - 1 || origin.v + reach > h - 1)
    return false;
  // The lattice's samples (offsets from the origin, px), their colors and
  // whether each is ball-colored or carpet-colored.
  std::array<float, kMaxSide * kMaxSide> du, dv;
  std::array<ColorVec, kMaxSide * kMaxSide> color;
  std::array<uint8_t, kMaxSide * kMaxSide> is_ball, is_carpet;
  int n = 0, n_ball = 0;
  for (int j = -half; j <= half; ++j)
    for (int i = -half; i <= half; ++i) {
      const double x = i * step, y = j * step;
      if (x * x + y * y > reach * reach) continue;
      float rgb[3];
      frameRgbAt(frame, origin.u + x, origin.v + y, rgb);
      du[n] = static_cast<float>(x), dv[n] = static_cast<float>(y);
      color[n] = pureChromaticity(rgb);
      is_ball[n] = test.isBall(rgb);
      is_carpet[n] = !is_ball[n] && test.isCarpet(rgb);
      n_ball += is_ball[n];
      ++n;
    }
  const double disc = kPi * r * r, window = kCentroidRadii * r;
  cu = cv = 0;
  bool whole = true;
  for (int pass = 0; pass < kPasses; ++pass) {
    double su = 0, sv = 0;
    int in = 0;
    for (int k = 0; k < n; ++k) {
      const double x = du[k] - cu, y = dv[k] - cv;
      if (!is_ball[k] || x * x + y * y > window * window) continue;
      su += du[k], sv += dv[k];
      ++in;
    }
    const double area = in * step * step;
    const double nu = in > 0 ? su / in : cu, nv = in > 0 ? sv / in : cv;
    const double moved = std::hypot(nu - cu, nv - cv);
    cu = nu, cv = nv;
    if (area < kMinAreaShare * disc || area > kMaxAreaShare * disc) {
      whole = false;
      break;
    }
    if (moved < 0.02 * step) break;
  }
  int beyond = 0;
  for (int k = 0; k < n; ++k) {
    const double x = du[k] - cu, y = dv[k] - cv;
    beyond += is_ball[k] && x * x + y * y > kRimRadii * kRimRadii * r * r;
  }
  const double beyond_part = beyond * step * step / disc;
  if (beyond_share) *beyond_share = beyond_part;
  if (!whole || beyond_part > kMaxBeyondRim) return false;
  softCentroid(du.data(), dv.data(), color.data(), is_ball.data(), is_carpet.data(), n, r, cu, cv);
  return true;
}

}  // namespace

bool ballColorBeyondRim(const FrameView& frame, const BallColorTest& test, ImagePx start, double r) {
  if (!frame.image || frame.image->empty() || r < 1) return false;
  double cu = 0, cv = 0, beyond = 0;
  settle(frame, test, start, r, cu, cv, &beyond);
  return beyond > kMaxBeyondRim;
}

bool ballSilhouetteCenter(const FrameView& frame, const BallColorTest& test, ImagePx start, double r,
                          ImagePx& center) {
  if (!frame.image || frame.image->empty() || r < 1) return false;
  // A center beyond the lattice's reach is settled again from there, once:
  // the blob may lie up to a radius off (a shaded ball's lit cap).
  ImagePx origin = start;
  for (int round = 0; round < 2; ++round) {
    double cu = 0, cv = 0;
    if (!settle(frame, test, origin, r, cu, cv)) return false;
    const ImagePx c{origin.u + cu, origin.v + cv};
    if (std::hypot(c.u - start.u, c.v - start.v) > r) return false;
    if (std::hypot(cu, cv) <= kReachRadii * r) {
      center = c;
      return true;
    }
    origin = c;
  }
  return false;
}

}  // namespace dv
