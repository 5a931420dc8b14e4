#include "detection/ring_orientation.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "detection/pattern_fit.h"
#include "geometry/robot_pattern.h"

namespace dv {
namespace {

double slotAngle(int slot) {
  const FieldMm o = patternOffset(slot);
  return std::atan2(o.y, o.x);
}

// Brightness along the ring; false where it leaves the image.
bool readRing(const FrameView& frame, const CameraModel& camera, const FieldPoint& center,
              std::array<float, kRingPoints>& bright) {
  if (!frame.image || frame.image->empty()) return false;
  const double r = RobotPatternGeometry::kSideBlobDistance;
  const double w = frame.image->cols, h = frame.image->rows;
  for (int i = 0; i < kRingPoints; ++i) {
    const double a = 2 * kPi * i / kRingPoints;
    const auto px = camera.fieldToImage({center.x + r * std::cos(a), center.y + r * std::sin(a), center.z});
    if (!px || px->u < 0 || px->v < 0 || px->u > w - 1 || px->v > h - 1) return false;
    float rgb[3];
    frameRgbAt(frame, px->u, px->v, rgb);
    bright[i] = rgb[0] + rgb[1] + rgb[2];
  }
  return true;
}

}  // namespace

std::optional<float> ringDarkest(const FrameView& frame, const CameraModel& camera, const FieldPoint& center) {
  std::array<float, kRingPoints> bright;
  if (!readRing(frame, camera, center, bright)) return std::nullopt;
  return *std::min_element(bright.begin(), bright.end());
}

std::optional<double> ringOrientation(const FrameView& frame, const CameraModel& camera, const FieldPoint& center,
                                      float min_bright) {
  std::array<float, kRingPoints> bright;
  if (!readRing(frame, camera, center, bright)) return std::nullopt;
  const auto [lo, hi] = std::minmax_element(bright.begin(), bright.end());
  const float thr = std::max(min_bright, 0.5f * (*lo + *hi));
  // Dots beside a black top, not the carpet's texture: the brightest
  // point at least kDotOverTop times the darkest (4.9 or more on the
  // sweeps' robots, 1.3 on bare carpet, 3.1 where a line crosses it).
  if (*hi < kDotOverTop * *lo) return std::nullopt;
  const double step = 2 * kPi / kRingPoints;
  auto ringIndex = [&](double a) {
    const int i = static_cast<int>(std::lround(a / step)) % kRingPoints;
    return i < 0 ? i + kRingPoints : i;
  };
  // Orientations (ring steps) that put every slot on a bright point and
  // the top between the dots on dark ones: ahead, where the front dots
  // leave 40 degrees of top between them, and at either side.
  const double gaps[3] = {0, 0.5 * (slotAngle(1) + slotAngle(2)), -0.5 * (slotAngle(1) + slotAngle(2))};
  std::array<bool, kRingPoints> fits;
  int n_fit = 0;
  for (int o = 0; o < kRingPoints; ++o) {
    fits[o] = true;
    for (int s = 1; s < kPatternSlots && fits[o]; ++s) fits[o] = bright[ringIndex(o * step + slotAngle(s))] >= thr;
    for (int g = 0; g < 3 && fits[o]; ++g) fits[o] = bright[ringIndex(o * step + gaps[g])] < thr;
    n_fit += fits[o];
  }
  // One run of them, no wider than a quarter turn (else the ring is bright
  // all round, or two orientations fit; two dots 65 degrees apart, each 36
  // degrees wide seen from the center, merge into one arc).
  if (n_fit == 0 || n_fit > kRingPoints / 4) return std::nullopt;
  int start = -1;
  for (int o = 0; o < kRingPoints; ++o)
    if (fits[o] && !fits[(o + kRingPoints - 1) % kRingPoints]) {
      if (start >= 0) return std::nullopt;  // a second run
      start = o;
    }
  if (start < 0) return std::nullopt;
  const double orientation = (start + 0.5 * (n_fit - 1)) * step;
  // Refined: each slot's bright arc centered on it, by brightness weight.
  double shift = 0;
  for (int s = 1; s < kPatternSlots; ++s) {
    const double at = orientation + slotAngle(s);
    const int mid = ringIndex(at);
    double w_sum = 0, a_sum = 0;
    for (int d = -3; d <= 3; ++d) {
      const float wt = bright[(mid + d + kRingPoints) % kRingPoints] - thr;
      if (wt <= 0) continue;
      w_sum += wt;
      a_sum += wt * wrapAngle((mid + d) * step - at);
    }
    if (w_sum > 0) shift += a_sum / w_sum / (kPatternSlots - 1);
  }
  return wrapAngle(orientation + shift);
}

}  // namespace dv
