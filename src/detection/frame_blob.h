#pragma once
// One blob of the frame as the detector's stages read it: the pixel stage's
// blob (pipeline/blob.h) moved onto the planes the stages search on, with
// its color. Blob indices in hypotheses and tracks refer to these.
#include <cmath>

#include "core/units.h"
#include "detection/color_classes.h"

namespace dv {

struct FrameBlob {
  FieldMm at_ref;      // on the plane hypotheses are searched on
  FieldMm at_team[2];  // at the yellow / blue robot height
  FieldMm at_ball;     // at the ball center height
  ColorVec color;
  float rgb[3] = {0, 0, 0};
  float score = 0;
  bool valid = false;
  bool weak = false;    // a weak peak (BlobList::weak), listed after the blobs
  bool streak = false;  // a fast-ball candidate: never part of a robot
  int robot = -1;       // accepted robot using this blob
  bool implausible_center = false;  // its robot was dropped for its center color
  // A strong blob clipped in two channels: the mean of its disc's samples
  // that clipped in none (its shaded rim; unclippedDiscColor), if any.
  bool has_unclipped = false;
  float unclipped_rgb[3] = {0, 0, 0};

  float brightness() const { return rgb[0] + rgb[1] + rgb[2]; }
};

// Brightness (r + g + b) as a share of the center blob's: a side blob is
// at least kTopBrightness (the markers are about as bright as the centers;
// darker peaks lie on the robot top) unless the top the frame shows is
// darker still (HypothesisSearch::darkerThanMarker), a marker read from the
// frame where no peak was found at least kMarkerBrightness.
constexpr float kTopBrightness = 0.33f, kMarkerBrightness = 0.5f;

namespace detector_detail {
inline double sq(double v) { return v * v; }
inline double dist(const FieldMm& a, const FieldMm& b) { return std::hypot(a.x - b.x, a.y - b.y); }
}  // namespace detector_detail

}  // namespace dv
