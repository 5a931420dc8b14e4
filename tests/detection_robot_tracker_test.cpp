// The robot tracker alone (detection/robot_tracker.h): prediction,
// association, identity hysteresis, unrelated scenes and recovery, on
// robots given by hand rather than found in frames.
#include <gtest/gtest.h>

#include <vector>

#include "detection/robot_tracker.h"

namespace dv {
namespace {

constexpr double kDt = 1.0 / 60;

Hypothesis robot(double x, double y, Team team, int id, uint8_t seen = 0xF) {
  Hypothesis h;
  h.pose.position = {x, y};
  h.pose.orientation = 0.3;
  h.pose.score = 1;
  h.team = team;
  h.id = id;
  h.colors = patternColors(id);
  h.seen_sides = seen;
  h.id_known = seen == 0xF;
  return h;
}

// Recovery as the detector does it, reduced to its outcome: the robot is
// found at the track's prediction, or (find = false) not at all.
struct Hooks : TrackHooks {
  bool find = false;
  std::vector<int> offered;  // track indices offered for recovery
  int refits = 0;
  bool recover(const RobotTrack& tr, int index, std::vector<Hypothesis>& out) override {
    offered.push_back(index);
    if (!find) return false;
    Hypothesis h = robot(tr.predicted.x, tr.predicted.y, tr.team, tr.id, 0x3);
    h.track = index;
    out.push_back(h);
    return true;
  }
  void refit(Hypothesis&) override { ++refits; }
};

// A robot that speeds up to 120 mm per frame (beyond the 90 mm gate from
// where it was) continues its track because the track predicts where it
// is now.
TEST(RobotTracker, FollowsAMovingRobotByItsPrediction) {
  RobotTracker tracker;
  Hooks hooks;
  const double x[] = {0, 80, 200, 320, 440};
  for (int f = 0; f < 5; ++f) {
    std::vector<Hypothesis> robots = {robot(x[f], 0, Team::Blue, 4)};
    EXPECT_FALSE(tracker.update(f * kDt, robots, hooks));
    ASSERT_EQ(tracker.tracks().size(), 1u);
    if (f >= 1) EXPECT_EQ(tracker.tracks()[0].history, 2) << "frame " << f << " started a new track";
    if (f >= 3) EXPECT_NEAR(tracker.tracks()[0].predicted.x, x[f], 1e-6);
  }
  EXPECT_TRUE(hooks.offered.empty());
}

// A certain identity changes only after identity_switch_frames frames
// agree on another; until then the robot is reported with the track's.
TEST(RobotTracker, IdentityHoldsUntilEnoughFramesAgree) {
  RobotTrackerOptions opt;
  opt.identity_switch_frames = 3;
  RobotTracker tracker(opt);
  Hooks hooks;
  std::vector<Hypothesis> robots = {robot(0, 0, Team::Yellow, 3)};
  tracker.update(0, robots, hooks);
  for (int f = 1; f <= 3; ++f) {
    robots = {robot(0, 0, Team::Yellow, 5)};
    tracker.update(f * kDt, robots, hooks);
    EXPECT_EQ(robots[0].id, f < 3 ? 3 : 5) << "frame " << f;
    EXPECT_TRUE(robots[0].id_known);
  }
  // A single contrary frame after the switch does not switch back.
  robots = {robot(0, 0, Team::Yellow, 3)};
  tracker.update(4 * kDt, robots, hooks);
  EXPECT_EQ(robots[0].id, 5);
}

// A team held against the frame's evidence is refitted at its own height.
TEST(RobotTracker, HeldTeamIsRefitted) {
  RobotTracker tracker;
  Hooks hooks;
  std::vector<Hypothesis> robots = {robot(0, 0, Team::Yellow, 3)};
  tracker.update(0, robots, hooks);
  robots = {robot(0, 0, Team::Blue, 3)};
  tracker.update(kDt, robots, hooks);
  EXPECT_EQ(robots[0].team, Team::Yellow);
  EXPECT_EQ(hooks.refits, 1);
}

// An id read from three sides is a guess: the first full view replaces it
// at once, and from then on the robot's id is known.
TEST(RobotTracker, GuessedIdYieldsToTheFirstFullView) {
  RobotTracker tracker;
  Hooks hooks;
  std::vector<Hypothesis> robots = {robot(0, 0, Team::Blue, 3, 0x7)};
  tracker.update(0, robots, hooks);
  EXPECT_FALSE(robots[0].id_known);
  robots = {robot(0, 0, Team::Blue, 5)};
  tracker.update(kDt, robots, hooks);
  EXPECT_EQ(robots[0].id, 5);
  EXPECT_TRUE(robots[0].id_known);
  EXPECT_TRUE(tracker.tracks()[0].id_certain);
}

// A partial view whose seen colors match the track's pattern agrees with
// it, whatever id the missing sides made it guess: no pending switch.
TEST(RobotTracker, PartialViewMatchingTheTrackKeepsItsId) {
  RobotTrackerOptions opt;
  opt.identity_switch_frames = 2;
  RobotTracker tracker(opt);
  Hooks hooks;
  std::vector<Hypothesis> robots = {robot(0, 0, Team::Blue, 3)};
  tracker.update(0, robots, hooks);
  for (int f = 1; f <= 4; ++f) {
    Hypothesis h = robot(0, 0, Team::Blue, 3, 0x3);  // two sides seen
    h.id = 12;  // a guess for the others
    robots = {h};
    tracker.update(f * kDt, robots, hooks);
    EXPECT_EQ(robots[0].id, 3) << "frame " << f;
    EXPECT_TRUE(robots[0].id_known);
  }
}

// Frames that meet fewer than half of the tracks show another scene: the
// tracks restart; a frame meeting most of them continues.
TEST(RobotTracker, UnrelatedSceneRestartsTheTracks) {
  RobotTracker tracker;
  Hooks hooks;
  auto frame = [](double dy, int moved) {
    std::vector<Hypothesis> r;
    for (int i = 0; i < 5; ++i) r.push_back(robot(500.0 * i, i < moved ? dy : 0, Team::Yellow, i));
    return r;
  };
  auto robots = frame(0, 0);
  EXPECT_FALSE(tracker.update(0, robots, hooks));
  robots = frame(1000, 2);  // 3 of 5 where they were
  EXPECT_FALSE(tracker.update(kDt, robots, hooks));
  hooks.offered.clear();  // the two that moved were offered
  robots = frame(-1000, 3);  // 2 of 5 where they were
  EXPECT_TRUE(tracker.update(2 * kDt, robots, hooks));
  ASSERT_EQ(tracker.tracks().size(), 5u);
  for (const auto& tr : tracker.tracks()) EXPECT_EQ(tr.history, 1);
  EXPECT_TRUE(hooks.offered.empty()) << "a dropped scene's tracks were offered for recovery";
}

// A track no robot continued is offered for recovery; recovered, it goes
// on with its identity, else it ends.
TEST(RobotTracker, UncontinuedTrackIsOfferedForRecovery) {
  for (bool find : {true, false}) {
    RobotTracker tracker;
    Hooks hooks;
    hooks.find = find;
    std::vector<Hypothesis> robots = {robot(0, 0, Team::Yellow, 1), robot(1000, 0, Team::Blue, 7)};
    tracker.update(0, robots, hooks);
    robots = {robot(0, 0, Team::Yellow, 1)};
    tracker.update(kDt, robots, hooks);
    ASSERT_EQ(hooks.offered.size(), 1u);
    if (find) {
      ASSERT_EQ(robots.size(), 2u);
      EXPECT_EQ(robots[1].id, 7);
      EXPECT_TRUE(robots[1].id_known) << "the track saw it whole";
      EXPECT_EQ(tracker.tracks().size(), 2u);
    } else {
      EXPECT_EQ(robots.size(), 1u);
      EXPECT_EQ(tracker.tracks().size(), 1u);
    }
  }
}

}  // namespace
}  // namespace dv
