#pragma once
// A robot's id from its side dots (thesis §5.3.5, per robot): its side
// blobs split by themselves into green and pink against its own center
// color (two colors on one robot: the redder is pink, whatever the cast),
// its weak peaks by the nearer of those two colors where clearly nearer,
// and the slots neither filled by the color the frame shows there
// (seen_color.h; all four dots in view split by themselves first). The
// frame's learned colors seed the split and stand in for a color the robot
// does not show. Which ids teammates rule out is partial_ids.h's.
#include <vector>

#include "detection/color_classes.h"
#include "detection/detector.h"
#include "detection/frame_blob.h"
#include "detection/robot_hypothesis.h"
#include "detection/seen_color.h"

namespace dv {

struct IdentityContext {
  const std::vector<FrameBlob>* blobs = nullptr;  // the hypotheses' blob indices refer to these
  ColorVec green, pink;                           // this frame's side colors
  FrameView frame;                                // may be empty: no slot is read
  const CameraModel* camera = nullptr;
  const DetectorOptions* opt = nullptr;
  float green_spread = 0, pink_spread = 0;  // of this frame's side colors (0: unknown)
  const ColorVec* white = nullptr;          // the lines' color this frame (null: not seen)
  bool sides_separated = false;             // green and pink split over the frame's side blobs
};

// Sets r.colors, r.seen_sides (bit s-1: slot s was seen) and r.id; r.team
// must be set (the slots are read at its height).
void identifyRobot(Hypothesis& r, const IdentityContext& context);

// The pattern refitted at its team's height (pattern offsets are mm on
// the robot top). Weak peaks sit less exactly than blobs: where the center
// and three side blobs are blobs, those alone give the pose. A center
// alone keeps its orientation and moves along its ray.
void refitAtTeamHeight(Hypothesis& h, const std::vector<FrameBlob>& blobs, double score_scale);

}  // namespace dv
