#include "detection/weak_sides.h"

#include <cmath>

namespace dv {

int findWeakSlots(const PatternPose& pose, unsigned filled, BlobIndex& weak, double tolerance,
                  int found[kPatternSlots], double error[kPatternSlots]) {
  int n = 0;
  for (int s = 0; s < kPatternSlots; ++s) {
    found[s] = -1;
    error[s] = tolerance;
    if (filled >> s & 1) continue;
    const FieldMm at = slotPosition(pose.position, pose.orientation, s);
    for (const auto& hit : weak.within(at, tolerance)) {
      const double d = std::sqrt(hit.second);
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
