// Which ball candidates are reported (detection/ball_policy.h).
#include "detection/ball_policy.h"

#include <gtest/gtest.h>

namespace dv {
namespace {

constexpr double kRadius = 21.5;

BallCandidate at(double x, double y, double confidence, bool streak = false, int track = -1, double rank = 0) {
  BallCandidate c;
  c.pos = {x, y};
  c.confidence = confidence;
  c.rank = rank > 0 ? rank : confidence;
  c.streak = streak;
  c.track = track;
  return c;
}

TEST(BallPolicy, OneBallPerPlaceTheMostConfident) {
  std::vector<BallCandidate> c = {at(0, 0, 0.6), at(50, 0, 0.9), at(1000, 0, 0.4)};
  selectBalls(c, kRadius, 4);
  ASSERT_EQ(c.size(), 2u);
  EXPECT_EQ(c[0].pos.x, 50);  // 50 mm from the other: the same ball
  EXPECT_EQ(c[1].pos.x, 1000);
}

TEST(BallPolicy, EqualConfidencesTheStrongerEvidenceFirst) {
  std::vector<BallCandidate> c = {at(0, 0, 1.0, false, -1, 1.2), at(30, 0, 1.0, false, -1, 2.5)};
  selectBalls(c, kRadius, 4);
  ASSERT_EQ(c.size(), 1u);
  EXPECT_EQ(c[0].pos.x, 30);
}

TEST(BallPolicy, AtMostMaxBalls) {
  std::vector<BallCandidate> c = {at(0, 0, 0.5), at(500, 0, 0.7), at(1000, 0, 0.9)};
  selectBalls(c, kRadius, 1);
  ASSERT_EQ(c.size(), 1u);
  EXPECT_EQ(c[0].pos.x, 1000);
}

TEST(BallPolicy, AStreakBesideARoundBallOnlyOnATrack) {
  // A streak that continues no track goes where a round blob is a ball ...
  std::vector<BallCandidate> c = {at(0, 0, 0.5), at(800, 0, 0.9, true)};
  selectBalls(c, kRadius, 4);
  ASSERT_EQ(c.size(), 1u);
  EXPECT_FALSE(c[0].streak);
  // ... stays where it continues one ...
  c = {at(0, 0, 0.5), at(800, 0, 0.9, true, 3)};
  selectBalls(c, kRadius, 4);
  EXPECT_EQ(c.size(), 2u);
  // ... and where it is the frame's only ball.
  c = {at(800, 0, 0.9, true)};
  selectBalls(c, kRadius, 4);
  EXPECT_EQ(c.size(), 1u);
}

}  // namespace
}  // namespace dv
