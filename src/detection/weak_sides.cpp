#include "detection/weak_sides.h"

#include <algorithm>
#include <cmath>

#include "detection/clipped_color.h"

namespace dv {

int findWeakSlots(const PatternPose& pose, unsigned filled, BlobIndex& weak, const FitTolerance& tolerance,
                  int found[kPatternSlots], double error[kPatternSlots]) {
  int n = 0;
  for (int s = 0; s < kPatternSlots; ++s) {
    found[s] = -1;
    error[s] = tolerance.mm;
    if (filled >> s & 1) continue;
    const FieldMm at = slotPosition(pose.position, pose.orientation, s);
    for (const auto& hit : weak.within(at, tolerance.mm * std::max(1.0, tolerance.stretch))) {
      double d = std::sqrt(hit.second);
      if (tolerance.stretch != 1) {
        const FieldMm& p = weak.points()[hit.first];
        const double ex = p.x - at.x, ey = p.y - at.y;
        const double along = (ex * tolerance.along_x + ey * tolerance.along_y) / tolerance.stretch;
        d = std::hypot(along, ey * tolerance.along_x - ex * tolerance.along_y);
      }
      if (d < error[s]) error[s] = d, found[s] = static_cast<int>(hit.first);
    }
    n += found[s] >= 0;
  }
  return n;
}

namespace {
int clearlyNearer(float dg, float dp, float margin) {
  if (dg < margin * dp) return 0;
  if (dp < margin * dg) return 1;
  return -1;
}
}  // namespace

int weakSideColor(const ColorVec& color, const ColorVec& green, const ColorVec& pink, float margin) {
  return clearlyNearer(colorDistance(color, green), colorDistance(color, pink), margin);
}

int sideColorOfDot(const ColorVec& color, const float rgb[3], const ColorVec& green, const ColorVec& pink,
                   float margin, MarkerColor& nearer) {
  // Two clipped channels fit nearly any hue: only what was seen counts.
  const ClippedColor seen(rgb);
  const bool one_clipped = seen.clipped() && !seen.saturated();
  const float dg = one_clipped ? seen.distance(green) : colorDistance(color, green);
  const float dp = one_clipped ? seen.distance(pink) : colorDistance(color, pink);
  nearer = dg <= dp ? MarkerColor::Green : MarkerColor::Pink;
  return clearlyNearer(dg, dp, margin);
}

}  // namespace dv
