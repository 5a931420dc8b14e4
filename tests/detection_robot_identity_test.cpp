// A robot's id from its dots on hand-made blobs (detection/robot_identity.h):
// the split of its own side colors, its weak peaks and the refit at its
// team's height.
#include <gtest/gtest.h>

#include <vector>

#include "detection/robot_identity.h"
#include "geometry/robot_pattern.h"

namespace dv {
namespace {

ColorVec feature(float r, float g, float b) { return colorFeature(r, g, b); }

struct RobotBlobs {
  std::vector<FrameBlob> blobs;
  Hypothesis robot;
  // A robot at `at` with the dots of `id`, drawn in `green` and `pink`;
  // `weak` (bit s-1): slot s is a weak peak.
  RobotBlobs(const FieldMm& at, double orientation, int id, const ColorVec& green, const ColorVec& pink,
             unsigned weak = 0) {
    const auto colors = patternColors(id);
    robot.n = kPatternSlots;
    for (int s = 0; s < kPatternSlots; ++s) {
      FrameBlob b;
      b.at_ref = s == 0 ? at : slotPosition(at, orientation, s);
      b.at_team[0] = b.at_team[1] = b.at_ref;
      b.color = s == 0 ? feature(90, 90, 230) : colors[s - 1] == MarkerColor::Green ? green : pink;
      b.weak = s > 0 && (weak >> (s - 1) & 1);
      b.valid = true;
      robot.blob[s] = s, robot.slot[s] = s;
      blobs.push_back(b);
    }
    robot.team = Team::Blue;
  }
};

IdentityContext context(const std::vector<FrameBlob>& blobs, const DetectorOptions& opt, const ColorVec& green,
                        const ColorVec& pink) {
  return {&blobs, green, pink, FrameView{}, nullptr, &opt};
}

TEST(RobotIdentity, EveryIdFromItsFourDots) {
  const DetectorOptions opt;
  const ColorVec green = feature(60, 200, 80), pink = feature(230, 90, 160);
  for (int id = 0; id < 16; ++id) {
    RobotBlobs r({1000, 500}, 0.3 * id, id, green, pink);
    identifyRobot(r.robot, context(r.blobs, opt, green, pink));
    EXPECT_EQ(r.robot.id, id);
    EXPECT_TRUE(r.robot.fullPattern()) << "id " << id;
  }
}

// Under a magenta cast a pale pink may lie nearer the frame's green than
// its pink; on one robot the redder of its two colors is pink all the same.
// (A robot of one color, ids 8 and 9, is judged by the frame's colors.)
TEST(RobotIdentity, TheRedderOfARobotsTwoColorsIsPink) {
  const DetectorOptions opt;
  const ColorVec frame_green = feature(150, 150, 140), frame_pink = feature(240, 60, 200);
  const ColorVec green = feature(120, 170, 130), pale_pink = feature(200, 130, 170);
  ASSERT_LT(colorDistance(pale_pink, frame_green), colorDistance(pale_pink, frame_pink));
  for (int id : {1, 6, 13, 14}) {
    RobotBlobs r({-500, 200}, 1.0, id, green, pale_pink);
    identifyRobot(r.robot, context(r.blobs, opt, frame_green, frame_pink));
    EXPECT_EQ(r.robot.id, id);
  }
}

// A weak peak takes the nearer of the robot's own two colors where clearly
// nearer; a weak peak of neither color leaves its slot unseen.
TEST(RobotIdentity, WeakPeaksTakeTheRobotsOwnColorsWhereClear) {
  const DetectorOptions opt;
  const ColorVec green = feature(60, 200, 80), pink = feature(230, 90, 160);
  RobotBlobs r({0, 0}, -0.5, 6, green, pink, /*weak=*/0b0100);
  identifyRobot(r.robot, context(r.blobs, opt, green, pink));
  EXPECT_EQ(r.robot.id, 6);
  EXPECT_TRUE(r.robot.fullPattern());
  RobotBlobs unclear({0, 0}, -0.5, 6, green, pink, 0b0100);
  unclear.blobs[3].color = feature(145, 168, 125);  // halfway: neither
  identifyRobot(unclear.robot, context(unclear.blobs, opt, green, pink));
  EXPECT_EQ(unclear.robot.seen_sides, 0b1011);
}

// One marker color split by its noise is one color: both halves lie within
// the frame's green class's reach. (H.265 at 3 Mbit/s under a green cast,
// chromaticities as read there: one of three green dots bluish; split off,
// it was taken for pink, and the robot's pink weak peak for green.)
TEST(RobotIdentity, TwoColorsWithinOneClasssReachAreOne) {
  DetectorOptions opt;
  auto chroma = [](float a, float b, float c) {
    ColorVec v;
    v.c[0] = a, v.c[1] = b, v.c[2] = c;
    return v;
  };
  const ColorVec frame_green = chroma(63, 149, 77), frame_pink = chroma(112, 85, 92);
  RobotBlobs r({800, -300}, 1.6, 14, chroma(57, 169, 63), chroma(109, 93, 88), /*weak=*/0b0001);  // P G G G
  r.blobs[0].color = chroma(110, 133, 49);  // a yellow center
  r.blobs[3].color = chroma(62, 143, 85);   // the bluish green, back left
  r.blobs[4].color = chroma(66, 154, 70);
  IdentityContext c = context(r.blobs, opt, frame_green, frame_pink);
  c.green_spread = 10, c.pink_spread = 3.6f;
  identifyRobot(r.robot, c);
  EXPECT_EQ(r.robot.id, 14);
  // Where the frame's green reaches less far (its dots alike), the bluish
  // one stands apart: the robot's own two colors.
  RobotBlobs apart({800, -300}, 1.6, 14, chroma(57, 169, 63), chroma(109, 93, 88), 0b0001);
  apart.blobs[0].color = chroma(110, 133, 49);
  apart.blobs[3].color = chroma(62, 143, 85);
  apart.blobs[4].color = chroma(66, 154, 70);
  IdentityContext narrow = context(apart.blobs, opt, frame_green, frame_pink);
  narrow.green_spread = 2;
  identifyRobot(apart.robot, narrow);
  EXPECT_NE(apart.robot.id, 14);
  // Two colors each nearer to its own class stay two, though both lie
  // within one class's reach (a pink class spread wide by uneven light).
  RobotBlobs two({800, -300}, 1.6, 7, chroma(80, 125, 85), chroma(110, 88, 92));  // P G P G
  two.blobs[0].color = chroma(110, 133, 49);
  IdentityContext wide = context(two.blobs, opt, frame_green, frame_pink);
  wide.green_spread = 3, wide.pink_spread = 20;
  ASSERT_LT(colorDistance(chroma(80, 125, 85), frame_pink), classReach(wide.pink_spread));
  identifyRobot(two.robot, wide);
  EXPECT_EQ(two.robot.id, 7);
}

// A center far out in color holds a robot's own split to a distance its
// dots do not reach (eq. 5.24; an amber center under a cold cast, moderate
// venue #1116); where the frame's side blobs split, its classes vouch for
// dots each clearly nearer to one of them.
TEST(RobotIdentity, AFarCenterColorLeavesTheSplitToTheFramesClasses) {
  const DetectorOptions opt;
  const ColorVec green = feature(84, 178, 169), pink = feature(198, 141, 231), amber = feature(207, 171, 10);
  ASSERT_LT(colorDistance(green, pink), 0.5f * colorDistance(pink, amber));
  for (int id : {1, 6, 13, 14}) {
    RobotBlobs r({-1400, 500}, 2.0, id, green, pink);
    r.blobs[0].color = amber;
    IdentityContext c = context(r.blobs, opt, feature(80, 170, 160), feature(200, 140, 225));
    identifyRobot(r.robot, c);
    EXPECT_NE(r.robot.id, id) << "the frame's sides did not split: the robot's own one cluster stands";
    c.sides_separated = true;
    identifyRobot(r.robot, c);
    EXPECT_EQ(r.robot.id, id);
  }
  // A dot clearly nearer to neither class vouches for nothing.
  RobotBlobs unclear({-1400, 500}, 2.0, 6, green, pink);
  unclear.blobs[0].color = amber;
  unclear.blobs[1].color = feature(141, 160, 200);
  IdentityContext c = context(unclear.blobs, opt, feature(80, 170, 160), feature(200, 140, 225));
  c.sides_separated = true;
  identifyRobot(unclear.robot, c);
  EXPECT_NE(unclear.robot.id, 6);
}

// Where three sides are blobs, a weak peak's position does not move the
// refitted pose.
TEST(RobotIdentity, RefitTrustsBlobsOverAWeakPeak) {
  const ColorVec green = feature(60, 200, 80), pink = feature(230, 90, 160);
  RobotBlobs r({300, -200}, 0.7, 3, green, pink, /*weak=*/0b0001);
  r.blobs[1].at_team[0] = r.blobs[1].at_team[1] = {r.blobs[1].at_ref.x + 8, r.blobs[1].at_ref.y - 6};
  refitAtTeamHeight(r.robot, r.blobs, 10);
  EXPECT_NEAR(r.robot.pose.position.x, 300, 0.01);
  EXPECT_NEAR(r.robot.pose.position.y, -200, 0.01);
  EXPECT_NEAR(r.robot.pose.orientation, 0.7, 1e-4);
}

}  // namespace
}  // namespace dv
