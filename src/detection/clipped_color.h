#pragma once
// Overexposure clips channels one by one: an orange ball whose red
// saturates first shows less red than it has, and its chromaticity moves
// toward yellow. A clipped channel says only "at least this much", so a
// blob is compared with a class by the nearest color that would clip to
// what was seen, not by the clipped color itself.
#include "detection/color_classes.h"

namespace dv {

// Mean channel level (0..255) from which a blob's channel counts as
// clipped: a saturated disc averages a little below 255 through its rim
// and the sensor noise.
inline constexpr float kClipLevel = 240.f;

// The candidate colors of one blob: its mean RGB, with each clipped channel
// free to grow up to kMaxClipGain times (a camera overexposed further shows
// nothing but white).
class ClippedColor {
 public:
  static constexpr float kMaxClipGain = 3.f;
  explicit ClippedColor(const float rgb[3]);
  // No channel clipped: the distance is the plain one.
  bool clipped() const { return n_clipped_ > 0; }
  // All three clipped: any chromaticity fits, the color says nothing.
  bool saturated() const { return n_clipped_ == 3; }
  // Smallest chromaticity distance from `c` to the candidate colors.
  float distance(const ColorVec& c) const;

 private:
  float rgb_[3];
  int clipped_[2] = {-1, -1};
  int n_clipped_ = 0;
};

}  // namespace dv
