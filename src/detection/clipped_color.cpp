#include "detection/clipped_color.h"

#include <algorithm>
#include <limits>

namespace dv {

namespace {
// Gain steps per clipped channel (1 .. kMaxClipGain): a chromaticity step
// of at most about 4 units, small against the class distances that decide.
constexpr int kSteps = 21;
}  // namespace

ClippedColor::ClippedColor(const float rgb[3]) {
  for (int c = 0; c < 3; ++c) {
    rgb_[c] = rgb[c];
    if (rgb[c] >= kClipLevel) {
      if (n_clipped_ < 2) clipped_[n_clipped_] = c;
      ++n_clipped_;
    }
  }
}

float ClippedColor::distance(const ColorVec& target) const {
  if (n_clipped_ == 0) return colorDistance(colorFeature(rgb_[0], rgb_[1], rgb_[2]), target);
  if (n_clipped_ == 3) return 0.f;
  const float step = (kMaxClipGain - 1.f) / (kSteps - 1);
  const int steps2 = n_clipped_ == 2 ? kSteps : 1;
  float best = std::numeric_limits<float>::max();
  float v[3] = {rgb_[0], rgb_[1], rgb_[2]};
  for (int i = 0; i < kSteps; ++i) {
    v[clipped_[0]] = rgb_[clipped_[0]] * (1.f + step * i);
    for (int j = 0; j < steps2; ++j) {
      if (n_clipped_ == 2) v[clipped_[1]] = rgb_[clipped_[1]] * (1.f + step * j);
      best = std::min(best, colorDistance(colorFeature(v[0], v[1], v[2]), target));
    }
  }
  return best;
}

}  // namespace dv
