#pragma once
// Which of a frame's ball candidates (ball_tracker.h's BallCandidate, each
// already judged by color, strength and track) are reported, and in what
// order: the most confident first (equal confidences: the stronger
// evidence), one ball per place, at most max_balls; and a fast-ball streak
// only where it continues a ball track (on its course or kicked from a
// robot) or where no round blob in the frame is a ball, since a colored
// region that stands out is weaker evidence than a round blob.
#include <vector>

#include "detection/ball_tracker.h"

namespace dv {

// Candidates within this many ball radii of a more confident one are the
// same ball (a ball diameter and its blur).
constexpr double kSameBallRadii = 4;

// Keeps the reported candidates of `cands`, in report order. No allocation.
void selectBalls(std::vector<BallCandidate>& cands, double ball_radius, int max_balls);

}  // namespace dv
