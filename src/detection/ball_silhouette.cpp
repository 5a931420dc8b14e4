#include "detection/ball_silhouette.h"

#include <algorithm>
#include <cmath>

namespace dv {
namespace {

// The window: a disc of this many ball radii around the current center,
// wide enough for a start half a radius off, narrow enough to leave the
// markers of a robot the ball touches outside.
constexpr double kWindowRadii = 1.6;
// Lattice spacing in radii, within [kMinStep, kMaxStep] px.
constexpr double kStepRadii = 0.1, kMinStep = 0.25, kMaxStep = 1.0;
// A whole ball's silhouette covers its disc, blurred by a pixel or so.
constexpr double kMinAreaShare = 0.6, kMaxAreaShare = 1.5;
constexpr int kPasses = 4;

}  // namespace

bool ballSilhouetteCenter(const FrameView& frame, const BallColorTest& test, ImagePx start, double r,
                          ImagePx& center) {
  if (!frame.image || frame.image->empty() || r < 1) return false;
  const double w = frame.image->cols, h = frame.image->rows;
  const double step = std::clamp(kStepRadii * r, kMinStep, kMaxStep);
  const double window = kWindowRadii * r;
  const int half = static_cast<int>(std::ceil(window / step));
  const double disc = kPi * r * r;
  ImagePx c = start;
  for (int pass = 0; pass < kPasses; ++pass) {
    // The whole window inside the image: a ball at the border is the
    // border finder's.
    if (c.u - window < 0 || c.v - window < 0 || c.u + window > w - 1 || c.v + window > h - 1) return false;
    double su = 0, sv = 0;
    int n = 0;
    for (int j = -half; j <= half; ++j)
      for (int i = -half; i <= half; ++i) {
        const double du = i * step, dv = j * step;
        if (du * du + dv * dv > window * window) continue;
        float rgb[3];
        frameRgbAt(frame, c.u + du, c.v + dv, rgb);
        if (!test.isBall(rgb)) continue;
        su += du, sv += dv;
        ++n;
      }
    const double area = n * step * step;
    if (area < kMinAreaShare * disc || area > kMaxAreaShare * disc) return false;
    const ImagePx next{c.u + su / n, c.v + sv / n};
    const double moved = std::hypot(next.u - c.u, next.v - c.v);
    c = next;
    if (moved < 0.02) break;
  }
  if (std::hypot(c.u - start.u, c.v - start.v) > r) return false;
  center = c;
  return true;
}

}  // namespace dv
