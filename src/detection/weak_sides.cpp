#include "detection/weak_sides.h"

#include <algorithm>
#include <cmath>

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

int weakSideColor(const ColorVec& color, const ColorVec& green, const ColorVec& pink, float margin) {
  const float dg = colorDistance(color, green), dp = colorDistance(color, pink);
  if (dg < margin * dp) return 0;
  if (dp < margin * dg) return 1;
  return -1;
}

}  // namespace dv
