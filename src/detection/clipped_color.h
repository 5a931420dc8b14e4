#pragma once
// Overexposure clips channels one by one: an orange ball whose red
// saturates first shows less red than it has, and its chromaticity moves
// toward yellow. A clipped channel says only "at least this much", so a
// blob is compared with a class by the nearest color that would clip to
// what was seen, not by the clipped color itself.
#include "detection/color_classes.h"
#include "pipeline/blob.h"  // kClipLevel

namespace dv {

// The candidate colors of one blob: its mean RGB, with a clipped channel
// free to grow up to kMaxClipGain times.
class ClippedColor {
 public:
  static constexpr float kMaxClipGain = 3.f;
  explicit ClippedColor(const float rgb[3]);
  const float* rgb() const { return rgb_; }  // as seen
  bool clipped() const { return n_clipped_ > 0; }
  // Two or three channels clipped: with two free channels nearly any hue
  // fits (a clipped yellow reaches orange), so the color says too little.
  bool saturated() const { return n_clipped_ >= 2; }
  // All three clipped: no hue is left, only "brighter than the sensor".
  bool white() const { return n_clipped_ == 3; }
  // Smallest chromaticity distance from `c` to the candidate colors; the
  // plain distance when nothing or everything clipped. Two clipped channels
  // grow together (the colors whose two channels are alike: a pale
  // yellow's red and green), or take `c`'s proportions scaled to the
  // unclipped channel where that clips both (a sky blue's green and blue);
  // for a saturated color, a lower bound on the nearest.
  float distance(const ColorVec& c) const;

 private:
  float rgb_[3];
  int clipped_ = -1;
  int n_clipped_ = 0;
};

}  // namespace dv
