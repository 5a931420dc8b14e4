#pragma once
// Fitting the standard robot pattern to a set of blobs (thesis §5.3.2) and
// the rule-shape tests used to filter robot hypotheses and balls.
#include <array>

#include "core/units.h"

namespace dv {

// Pattern slots: 0 = center blob, 1..4 = side blobs in SideBlob order + 1
// (FL, BL, BR, FR: increasing angle from the front).
constexpr int kPatternSlots = 5;
// Slot offsets in the robot frame (mm on the robot top).
FieldMm patternOffset(int slot);

struct PatternPose {
  FieldMm position;        // robot center
  double orientation = 0;  // rad
  double score = 0;        // eq. 5.21: min over blobs of 1 / (1 + (e/scale)^2)
};

// Least-squares rigid fit (2-D Procrustes) of the pattern slots `slots` to
// `points` (same order, n >= 2). This is the optimum that eq. 5.19/5.20 (the
// mean of pair angles, then the mean offset) approximate; with exact data
// both agree. `score_scale` in mm (10 in the thesis).
PatternPose fitPattern(const FieldMm* points, const int* slots, int n, double score_scale);

// The offset giving score 0.5, where a tilted camera sees the robot: a
// pixel covers more field along the viewing ray than across it, so a far
// blob's position is that much less certain along the ray. `mm` across the
// ray, `stretch` times that along the unit direction (along_x, along_y).
struct FitTolerance {
  double mm = 10;
  double along_x = 1, along_y = 0;
  double stretch = 1;  // 1: round, the plain score
};
PatternPose fitPattern(const FieldMm* points, const int* slots, int n, const FitTolerance& tolerance);

// Position of `slot` for a robot at `pose`.
FieldMm slotPosition(const FieldMm& position, double orientation, int slot);

// The rule's minimal robot top: a disc of radius 85 mm cut flat 55 mm in
// front of the center. True when the tops of two robots, each shrunk by
// `tolerance` mm, would intersect (so both cannot be real).
bool robotTopsOverlap(const FieldMm& a, double orientation_a, const FieldMm& b,
                      double orientation_b, double tolerance = 3);

// Distance (mm) from `p` to the minimal robot top of a robot at `center` with
// `orientation`; 0 inside.
double distanceToRobotTop(const FieldMm& p, const FieldMm& center, double orientation);

// How far a ball center must stay outside the robot's top so that at least
// 80 % of the ball's area (seen from above) lies outside it (rules), for a
// ball of `ball_radius`: 0.4919 r.
double minBallOutsideDistance(double ball_radius);

// Angle wrapped to (-pi, pi].
double wrapAngle(double a);

}  // namespace dv
