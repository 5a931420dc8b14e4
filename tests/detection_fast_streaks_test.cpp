// Blobs no color rule takes, linked across frames (fast_streaks.h): a fast
// straight chain is a ball, a slow thing's blobs and scattered clutter are
// none.
#include <gtest/gtest.h>

#include <cmath>

#include "detection/fast_streaks.h"

namespace dv {
namespace {

constexpr double kDt = 1.0 / 60;

FastStreaks limits() {
  FastStreaks s;
  s.setLimits(4000, 6500, 21.5);
  return s;
}

// Frames 0.. of a ball rolling at (vx, vy) mm/s from (x0, y0), each frame
// added before the next begins; the confidence of the last one.
double rolling(FastStreaks& s, int frames, double vx, double vy, double x0 = 0, double y0 = 0) {
  double c = 0;
  for (int f = 0; f < frames; ++f) {
    s.begin(f * kDt);
    const FieldMm p{x0 + vx * f * kDt, y0 + vy * f * kDt};
    c = s.confidence(p);
    s.add(p);
  }
  return c;
}

TEST(FastStreaks, AThirdBlobOnAFastStraightCourseIsTheBall) {
  FastStreaks s = limits();
  EXPECT_EQ(rolling(s, 2, 5400, -3240), 0.0);  // two blobs make no course
  s = limits();
  EXPECT_NEAR(rolling(s, 3, 5400, -3240), 1.0, 1e-9);
}

TEST(FastStreaks, NoChainAsSlowAsARobotOrFasterThanABall) {
  FastStreaks s = limits();
  EXPECT_EQ(rolling(s, 4, 3000, 0), 0.0);
  s = limits();
  EXPECT_EQ(rolling(s, 4, 8000, 0), 0.0);
}

// A frame without the blob (a compressed stream's lost frame) leaves the
// chain: the pair may span it.
TEST(FastStreaks, AChainSpansAFrameWithoutTheBlob) {
  FastStreaks s = limits();
  for (int f = 0; f < 4; ++f) {
    s.begin(f * kDt);
    if (f == 2) continue;
    const FieldMm p{6000 * f * kDt, 0};
    if (f == 3) {
      EXPECT_NEAR(s.confidence(p), 1.0, 1e-9);
    }
    s.add(p);
  }
}

// The place a pair predicts: within two ball radii the confidence falls
// with the distance from it; beyond, nothing.
TEST(FastStreaks, OffTheCourseByMoreThanABallsPictureIsNone) {
  for (double off : {20.0, 50.0}) {
    FastStreaks s = limits();
    for (int f = 0; f < 3; ++f) {
      s.begin(f * kDt);
      const FieldMm p{6000 * f * kDt, f == 2 ? off : 0.0};
      if (f == 2) {
        if (off < 2 * 21.5)
          EXPECT_NEAR(s.confidence(p), 1 - off / std::hypot(100.0, off), 1e-9);
        else
          EXPECT_EQ(s.confidence(p), 0.0);
      }
      s.add(p);
    }
  }
}

// The dots of a robot not found stay put from frame to frame: a blob with
// one of the frame before within a robot's reach is no ball, though three
// others line up with it.
TEST(FastStreaks, ABlobWhereASlowThingWasIsNone) {
  FastStreaks s = limits();
  for (int f = 0; f < 3; ++f) {
    s.begin(f * kDt);
    const FieldMm p{6000 * f * kDt, 0};
    if (f == 2) {
      EXPECT_EQ(s.confidence(p), 0.0);
    }
    s.add(p);
    s.add({6000 * 2 * kDt + 30, 10});  // a dot beside where the ball arrives
  }
}

// clear() forgets the frames before (a new scene).
TEST(FastStreaks, ClearedItLinksNothing) {
  FastStreaks s = limits();
  rolling(s, 2, 6000, 0);
  s.clear();
  s.begin(2 * kDt);
  EXPECT_EQ(s.confidence({200, 0}), 0.0);
}

}  // namespace
}  // namespace dv
