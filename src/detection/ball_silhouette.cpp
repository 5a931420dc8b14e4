#include "detection/ball_silhouette.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace dv {
namespace {

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
constexpr int kMaxSide = 2 * static_cast<int>((kCentroidRadii + kReachRadii) / kStepRadii) + 3;

// The centroid of the ball-colored samples near `origin`, whose lattice is
// judged once; false where the silhouette is no whole ball alone. (cu, cv):
// the center from the origin (px).
bool settle(const FrameView& frame, const BallColorTest& test, ImagePx origin, double r, double& cu, double& cv) {
  const double step = kStepRadii * r;
  const double reach = (kCentroidRadii + kReachRadii) * r;
  const int half = std::min(static_cast<int>(std::ceil(reach / step)), (kMaxSide - 1) / 2);
  // The whole lattice inside the image: a ball at the border is the border
  // finder's.
  const double w = frame.image->cols, h = frame.image->rows;
  if (origin.u - reach < 0 || origin.v - reach < 0 || origin.u + reach > w - 1 || origin.v + reach > h - 1)
    return false;
  // Ball-colored samples of the lattice (offsets from the origin, px).
  std::array<float, kMaxSide * kMaxSide> du, dv;
  int n_ball = 0;
  for (int j = -half; j <= half; ++j)
    for (int i = -half; i <= half; ++i) {
      const double x = i * step, y = j * step;
      if (x * x + y * y > reach * reach) continue;
      float rgb[3];
      frameRgbAt(frame, origin.u + x, origin.v + y, rgb);
      if (!test.isBall(rgb)) continue;
      du[n_ball] = static_cast<float>(x), dv[n_ball] = static_cast<float>(y);
      ++n_ball;
    }
  const double disc = kPi * r * r, window = kCentroidRadii * r;
  cu = cv = 0;
  for (int pass = 0; pass < kPasses; ++pass) {
    double su = 0, sv = 0;
    int n = 0;
    for (int k = 0; k < n_ball; ++k) {
      const double x = du[k] - cu, y = dv[k] - cv;
      if (x * x + y * y > window * window) continue;
      su += du[k], sv += dv[k];
      ++n;
    }
    const double area = n * step * step;
    if (area < kMinAreaShare * disc || area > kMaxAreaShare * disc) return false;
    const double nu = su / n, nv = sv / n;
    const double moved = std::hypot(nu - cu, nv - cv);
    cu = nu, cv = nv;
    if (moved < 0.02 * step) break;
  }
  int beyond = 0;
  for (int k = 0; k < n_ball; ++k) {
    const double x = du[k] - cu, y = dv[k] - cv;
    beyond += x * x + y * y > kRimRadii * kRimRadii * r * r;
  }
  return beyond * step * step <= kMaxBeyondRim * disc;
}

}  // namespace

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
