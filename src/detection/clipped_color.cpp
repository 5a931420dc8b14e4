#include "detection/clipped_color.h"

#include <algorithm>

namespace dv {

namespace {
// Gain steps for the clipped channel (1 .. kMaxClipGain): a chromaticity
// step of at most about 4 units, small against the class distances.
constexpr int kSteps = 21;
}  // namespace

ClippedColor::ClippedColor(const float rgb[3]) {
  for (int c = 0; c < 3; ++c) {
    rgb_[c] = rgb[c];
    if (rgb[c] >= kClipLevel) clipped_ = c, ++n_clipped_;
  }
}

float ClippedColor::distance(const ColorVec& target) const {
  float v[3] = {rgb_[0], rgb_[1], rgb_[2]};
  float best = colorDistance(colorFeature(v[0], v[1], v[2]), target);
  if (n_clipped_ == 0 || n_clipped_ == 3) return best;
  const float step = (kMaxClipGain - 1.f) / (kSteps - 1);
  for (int i = 1; i < kSteps; ++i) {
    for (int c = 0; c < 3; ++c)
      if (rgb_[c] >= kClipLevel) v[c] = rgb_[c] * (1.f + step * i);
    best = std::min(best, colorDistance(colorFeature(v[0], v[1], v[2]), target));
  }
  if (n_clipped_ == 2) {
    // Two clipped channels need not have grown alike: the target's own
    // proportions, scaled to the unclipped channel, where its clipped
    // channels would have clipped too (within kMaxClipGain). A sky-blue
    // center clipped in green and blue, (138, 255, 255), is the team's
    // blue, and no line: a white that clips green shows more red.
    int u = 0;
    while (rgb_[u] >= kClipLevel) ++u;
    if (target.c[u] > 0) {
      const float s = rgb_[u] / target.c[u];
      for (int c = 0; c < 3; ++c)
        v[c] = c == u ? rgb_[c] : std::clamp(s * target.c[c], rgb_[c], kMaxClipGain * rgb_[c]);
      best = std::min(best, colorDistance(colorFeature(v[0], v[1], v[2]), target));
    }
  }
  return best;
}

}  // namespace dv
