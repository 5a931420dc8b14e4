// The ball tracker alone (detection/ball_tracker.h): prediction at the
// walls, kicks next to robots, stale pictures, echoes and gaps, on
// candidates given by hand rather than found in frames.
#include <gtest/gtest.h>

#include <vector>

#include "detection/ball_tracker.h"

namespace dv {
namespace {

constexpr double kDt = 1.0 / 60;

BallTrackerOptions options() {
  BallTrackerOptions o;
  o.area = {-4800, 4800, -3300, 3300};
  return o;
}

BallCandidate ball(double x, double y, double rank = 1, bool streak = false) {
  BallCandidate c;
  c.pos = {x, y};
  c.rank = rank;
  c.confidence = rank;
  c.streak = streak;
  return c;
}

// One frame: predict, match each candidate, update. Returns what is kept.
std::vector<BallCandidate> frame(BallTracker& tracker, double t, std::vector<BallCandidate> cands,
                                 const std::vector<FieldMm>& robots = {}) {
  tracker.predict(t, robots.data(), static_cast<int>(robots.size()));
  for (auto& c : cands) tracker.match(c);
  tracker.update(t, cands);
  return cands;
}

// 3 m/s toward the +x wall (x = 4800 - radius for the ball's center): the
// prediction past the wall is mirrored back into the field.
TEST(BallTracker, PredictionBouncesOffTheWalls) {
  BallTracker tracker(options());
  const double wall = 4800 - 21.5;
  frame(tracker, 0, {ball(wall - 90, 0)});
  frame(tracker, kDt, {ball(wall - 40, 0)});
  tracker.predict(2 * kDt, nullptr, 0);
  ASSERT_EQ(tracker.tracks().size(), 1u);
  EXPECT_NEAR(tracker.tracks()[0].predicted.x, wall - 10, 1e-6);  // 50 mm on: 10 past the wall
  BallCandidate back = ball(wall - 12, 0);
  tracker.match(back);
  EXPECT_EQ(back.track, 0);
  EXPECT_FALSE(back.kicked);
}

// Next to a robot a ball may leave in any direction: a candidate off the
// course continues the track as kicked. Far from robots it does not.
TEST(BallTracker, KickedNextToARobotOnly) {
  for (bool robot : {true, false}) {
    BallTracker tracker(options());
    std::vector<FieldMm> robots;
    if (robot) robots.push_back({-110, 0});
    frame(tracker, 0, {ball(0, 0)}, robots);
    frame(tracker, kDt, {ball(0, 0)}, robots);
    tracker.predict(2 * kDt, robots.data(), static_cast<int>(robots.size()));
    BallCandidate kicked = ball(0, 120);  // beyond the course gate (84 mm), within the kick gate
    tracker.match(kicked);
    EXPECT_EQ(kicked.track, robot ? 0 : -1) << (robot ? "next to a robot" : "alone");
    EXPECT_EQ(kicked.kicked, robot);
  }
}

// A ball rolling at 3 m/s, and a weaker candidate where it lay two frames
// ago (a stream's stale blocks): an echo, dropped. One beside the course
// is another ball, kept.
TEST(BallTracker, EchoesOnTheCourseAreDropped) {
  BallTracker tracker(options());
  for (int f = 0; f < 3; ++f) frame(tracker, f * kDt, {ball(50.0 * f, 0)});
  const auto kept = frame(tracker, 3 * kDt, {ball(150, 0), ball(50, 0, 0.5), ball(50, 300, 0.5)});
  ASSERT_EQ(kept.size(), 2u);
  EXPECT_EQ(kept[0].pos.x, 150);
  EXPECT_EQ(kept[1].pos.y, 300);
}

// A kicked ball shows as a streak on its way and as a round blob where it
// lay (a compressed stream's copied blocks): the round blob is stale.
TEST(BallTracker, StreakTakesTheTrackFromAStalePicture) {
  BallTracker tracker(options());
  const std::vector<FieldMm> robots = {{-110, 0}};
  frame(tracker, 0, {ball(0, 0)}, robots);
  frame(tracker, kDt, {ball(0, 0)}, robots);
  const auto kept = frame(tracker, 2 * kDt, {ball(0, 0, 1.0), ball(90, 0, 0.7, true)}, robots);
  ASSERT_EQ(kept.size(), 1u);
  EXPECT_TRUE(kept[0].streak);
  EXPECT_EQ(kept[0].track, 0);
  EXPECT_EQ(tracker.tracks()[0].pos[1].x, 90);
}

// An unconfirmed track survives a 0.1 s gap (flicker, occlusion) and
// continues after it; after a longer one it is gone.
TEST(BallTracker, TracksSurviveShortGapsOnly) {
  for (int gap : {5, 8}) {
    BallTracker tracker(options());
    frame(tracker, 0, {ball(0, 0)});
    frame(tracker, kDt, {ball(10, 0)});
    for (int f = 2; f < 2 + gap; ++f) frame(tracker, f * kDt, {});
    EXPECT_EQ(tracker.tracks().size(), gap * kDt <= 0.1 ? 1u : 0u) << "gap of " << gap << " frames";
  }
}

// Only a track faster than any robot is expected anywhere in the next
// frame, where its course takes it (also across a frame it was missed in).
TEST(BallTracker, OnlyAFastBallIsExpectedAndOnItsCourse) {
  BallTracker tracker(options());
  FieldMm at[4];
  frame(tracker, 0, {ball(0, 0), ball(1000, 1000)});
  frame(tracker, kDt, {ball(100, 0), ball(1030, 1000)});  // 6 m/s and 1.8 m/s
  ASSERT_EQ(tracker.expectedFastBalls(2 * kDt, at, 4), 1);
  EXPECT_NEAR(at[0].x, 200, 1e-6);
  EXPECT_NEAR(at[0].y, 0, 1e-6);
  frame(tracker, 2 * kDt, {ball(1060, 1000)});  // the fast ball missed once
  ASSERT_EQ(tracker.expectedFastBalls(3 * kDt, at, 4), 1);
  EXPECT_NEAR(at[0].x, 300, 1e-6);
  EXPECT_EQ(tracker.expectedFastBalls(3 * kDt, at, 0), 0);  // no room
}

// A candidate only its course vouches for is kept, but neither moves its
// track (which goes on from its last blob) nor starts one.
TEST(BallTracker, ACourseOnlyCandidateNeitherMovesNorStartsATrack) {
  BallTracker tracker(options());
  frame(tracker, 0, {ball(0, 0)});
  frame(tracker, kDt, {ball(100, 0)});
  BallCandidate weak = ball(230, 10), elsewhere = ball(-2000, 500);
  weak.course_only = elsewhere.course_only = true;
  const auto kept = frame(tracker, 2 * kDt, {weak, elsewhere});
  EXPECT_EQ(kept.size(), 2u);
  ASSERT_EQ(tracker.tracks().size(), 1u);
  EXPECT_EQ(tracker.tracks()[0].pos[1].x, 100);
  frame(tracker, 3 * kDt, {ball(300, 0)});  // straight on from the last blob
  EXPECT_EQ(tracker.tracks().size(), 1u);
  EXPECT_EQ(tracker.tracks()[0].pos[1].x, 300);
}

}  // namespace
}  // namespace dv
