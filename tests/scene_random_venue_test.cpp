// Venues drawn by scripts/random_venues.py (one frame each at 1224 x 1024,
// 8 + 8 robots, shipped defaults) that showed a rule missing: each scene as
// the script wrote it, held to the bar its rule gave.
#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>

#include "scene_scoring.h"
#include "synth/scene.h"

namespace dv {
namespace {

using namespace dv::test;

// What the script draws per venue (its YAML keys); the sun patch lies over
// the ball (600 x 500 mm, angle 0.3, softness 0.25), none where its gain is 0.
struct Venue {
  int seed;
  double ball_x, ball_y;
  std::array<int, 3> pink, green, yellow, blue, ball;
  std::array<double, 3> white_balance;
  double saturation, gamma, exposure, uneven_ratio, uneven_direction, sun_gain;
};

// The venue as the script writes it, scored at half resolution; without
// `ball_in_view` the ball lies on the other half, out of the camera's view
// (the sun patch stays where the script put it).
SceneScore venueScore(const Venue& v, bool ball_in_view = true) {
  auto rgb = [](const std::array<int, 3>& c) {
    return "[" + std::to_string(c[0]) + ", " + std::to_string(c[1]) + ", " + std::to_string(c[2]) + "]";
  };
  char ball[64], sun_at[64], lighting[512];
  std::snprintf(sun_at, sizeof sun_at, "[%.0f, %.0f]", v.ball_x, v.ball_y);
  std::snprintf(ball, sizeof ball, "[%.0f, %.0f]", ball_in_view ? v.ball_x : 2500.0, ball_in_view ? v.ball_y : 0.0);
  std::snprintf(lighting, sizeof lighting,
                "lighting:\n  white_balance: [%.2f, %.2f, %.2f]\n  saturation: %.2f\n  gamma: %.2f\n"
                "  exposure: %.2f\n  uneven_ratio: %.2f\n  uneven_direction: %.2f\n",
                v.white_balance[0], v.white_balance[1], v.white_balance[2], v.saturation, v.gamma, v.exposure,
                v.uneven_ratio, v.uneven_direction);
  char sun[160] = "";
  if (v.sun_gain > 0)
    std::snprintf(sun, sizeof sun,
                  "  sun_patches:\n    - {center: %s, radii: [600, 500], angle: 0.3, gain: %.2f, softness: 0.25}\n",
                  sun_at, v.sun_gain);
  const std::string n = std::to_string(v.seed);
  const std::string yaml = "name: venue_" + n + "\nseed: " + n + R"(
field: division_b
cameras:
  - {id: 0, position: [-2250, 0, 5000], look_at: [-2250, 0, 0], up: [-1, 0, 0], focal_length: 1750,
     distortion: 0.03, principal_offset: [6.5, -4.0], size: [2448, 2048]}
noise_sigma: 1.5
shot_noise: 0.05
lens_blur_px: 0.6
antialias: 2
frames: 1
bayer: true
)" + "ball: {position: " + ball + "}\nrandom_robots: {yellow: 8, blue: 8, camera: 0, margin_px: 60, seed: " + n +
                           "}\nmaterials:\n  pink: " + rgb(v.pink) + "\n  green: " + rgb(v.green) +
                           "\n  yellow: " + rgb(v.yellow) + "\n  blue: " + rgb(v.blue) + "\n  ball: " + rgb(v.ball) +
                           "\n" + lighting + sun;
  SceneSpec s = sceneFromYaml(yaml, "venue_" + n);
  halveResolution(s);
  SceneScore score_;
  score(s, 1, true, score_);
  return score_;
}

// Moderate venue #376: a sun patch (1.9) under a cold cast at saturation
// 0.82 lights one green dot of an all-green robot toward white, (222, 250,
// 220). Its three other dots peaked; the read of the fourth split from them
// as the redder, so pink: id 14 for 8. A dot read where no blob was must
// lie on its label's side of the lines' white (robot_identity.cpp).
TEST(SceneRandomVenue, AGreenDotLitTowardWhiteStaysGreen) {
  const SceneScore s = venueScore({376, -3714, -242, {255, 140, 190}, {111, 197, 79}, {243, 217, 56}, {47, 90, 173},
                                   {244, 83, 20}, {0.99, 1.09, 1.34}, 0.82, 0.76, 0.98, 1.51, -2.00, 1.90});
  EXPECT_EQ(s.precision(), 1.0);
  EXPECT_EQ(s.idAccuracy(), 1.0);
}

// Extreme venue #157: a brighter sun patch (2.05) under a magenta cast at
// saturation 0.41 clips a pink dot to (242, 247, 241), which has no hue
// left: by its side of the lines' white it read green (id 8 for 2). Such
// a dot keeps the label the split gives it, the redder of the robot's dots.
TEST(SceneRandomVenue, ADotClippedWhiteKeepsItsSplit) {
  const SceneScore s = venueScore({157, -2607, -575, {249, 118, 183}, {137, 206, 60}, {241, 232, 71}, {42, 80, 164},
                                   {242, 76, 20}, {1.05, 0.89, 1.27}, 0.41, 0.95, 0.94, 2.63, -2.57, 2.05});
  EXPECT_EQ(s.precision(), 1.0);
  EXPECT_EQ(s.idAccuracy(), 1.0);
}

// Extreme venue #282: a blue robot by the image's corner shows two green
// dots, (167, 240, 164) and (177, 246, 169), and beside them two pink dots
// lit toward white under uneven light of 2.9, (234, 236, 224) and one
// clipped in green; none peaked. Too pale to split from the greens against
// the blue center (eq. 5.24), both were guessed green: id 8 for 11. A dot
// that no color the robot's seen dots may have (a clipped channel free to
// grow) comes near is the other color (robot_identity.cpp); the robot is
// then one of two ids, and at two side blobs not reported.
TEST(SceneRandomVenue, APaleDotNoSeenColorExplainsIsTheOtherColor) {
  const SceneScore s = venueScore({282, -2434, 573, {254, 135, 188}, {112, 197, 79}, {245, 202, 39}, {30, 59, 146},
                                   {245, 87, 20}, {1.00, 1.18, 1.34}, 0.83, 1.50, 1.21, 2.95, -2.19, 0});
  EXPECT_EQ(s.precision(), 1.0);
  EXPECT_EQ(s.idAccuracy(), 1.0);
}

// Extreme venue #383: blue 2's three green dots peaked, (158, 247, 235),
// clipped in green; its pink, lit toward white under uneven light of 3,
// read (238, 247, 239), clipped in green as they are, and made no peak.
// Guessed green, the robot was reported as 8. Red to blue, the two
// channels neither clipped, it shows 1.00 against the greens' 0.67: no
// green (mayBeOneColor).
TEST(SceneRandomVenue, ADotClippedAsItsNeighboursAreIsJudgedByTheRest) {
  const SceneScore s = venueScore({383, -859, 1488, {250, 120, 184}, {52, 177, 124}, {247, 187, 24}, {21, 42, 132},
                                   {251, 106, 20}, {1.14, 1.01, 1.17}, 0.53, 1.08, 1.27, 3.00, -1.26, 1.51});
  EXPECT_EQ(s.recall(), 1.0);
  EXPECT_EQ(s.precision(), 1.0);
  EXPECT_EQ(s.idAccuracy(), 1.0);
}

// Extreme venue #56: a sun patch of 2.24 over the ball under a cold cast
// lights the carpet around it into weak peaks where a pattern's dots would
// lie: a robot of the clipped ball and the carpet, and no ball. A weak peak
// colored as the carpet just beyond the robot's rim, and no brighter than
// a marker over it, is no marker (hypothesis_search.cpp).
TEST(SceneRandomVenue, ALitBallAmongCarpetPeaksIsNoRobot) {
  const SceneScore s = venueScore({56, -3216, 1243, {249, 117, 183}, {105, 195, 84}, {241, 235, 75}, {45, 86, 169},
                                   {240, 70, 20}, {0.73, 1.02, 1.66}, 0.83, 1.12, 1.26, 2.98, -0.50, 2.24});
  EXPECT_EQ(s.precision(), 1.0);
  EXPECT_EQ(s.ballRecall(), 1.0);
}

// Moderate venue #470: under a warm cast (1.56, 0.94, 0.65) at saturation
// 0.52 the sky-blue centers read (160, 180, 175), as gray as the lines: no
// blob peaked there and no class placed them, so the blue team was never
// seen. The centers of full patterns no class places are clustered with
// the seen team's (detector_unpeaked_centers.cpp, learnUnseenTeam).
TEST(SceneRandomVenue, ATeamAsGrayAsTheLinesIsLearnedFromItsPatterns) {
  const SceneScore s = venueScore({470, -1445, -2029, {238, 71, 169}, {52, 177, 123}, {241, 236, 75}, {87, 164, 235},
                                   {250, 103, 20}, {1.56, 0.94, 0.65}, 0.52, 1.50, 1.03, 1.88, 1.31, 1.92});
  EXPECT_GE(s.recall(), 15.0 / 16);
  EXPECT_EQ(s.precision(), 1.0);
  EXPECT_EQ(s.idAccuracy(), 1.0);
}

// Extreme venue #284: under a warm cast (1.57, 0.91, 0.64) at exposure 1.3
// and uneven light 2.7, the amber centers clip in red and green in the
// brighter half, (252, 253, 171), and split from the unclipped ones as the
// bluer cluster: six yellow robots reported blue, while the sky-blue
// centers, as gray as the lines, made no blob. A cluster of clipped centers
// that the other's color explains is that color (clusterCenters); the
// unseen team's split is then learned from the unclipped centers.
TEST(SceneRandomVenue, AnAmberTeamClippedInTheLightIsOneTeam) {
  const SceneScore s = venueScore({284, -3181, 857, {251, 122, 185}, {111, 197, 80}, {248, 179, 14}, {86, 162, 234},
                                   {246, 89, 20}, {1.57, 0.91, 0.64}, 0.49, 1.05, 1.30, 2.66, -0.17, 0});
  EXPECT_GE(s.recall(), 15.0 / 16);
  EXPECT_EQ(s.precision(), 1.0);
  EXPECT_EQ(s.idAccuracy(), 1.0);
}

// Extreme venue #299: at saturation 0.41 and gamma 1.49 a light orange ball
// reads (218, 156, 96), nearest to the amber centers (232, 181, 95), and
// is judged as a ball of the yellow class's color, round and alone. The
// centers clipped in red and green ((250, 252, 194) in the brighter half)
// had widened that class's reach over the carpet beyond the ball's rim: no
// ball. A clipped center's distance to its team is now the nearest color
// that clips to it (learnFrameColors).
TEST(SceneRandomVenue, ClippedCentersWidenNoTeamOverTheCarpet) {
  const SceneScore s = venueScore({299, -1483, -770, {231, 44, 161}, {79, 186, 104}, {246, 193, 30}, {87, 164, 235},
                                   {254, 116, 20}, {1.27, 1.09, 1.00}, 0.41, 1.49, 1.26, 2.36, 0.58, 0});
  EXPECT_EQ(s.ballRecall(), 1.0);
  EXPECT_EQ(s.ballPrecision(), 1.0);
  EXPECT_EQ(s.precision(), 1.0);
}

// Moderate venue #475: a sun patch of 2.09 under a cold cast clips a lemon
// center to white (251, 254, 252) among four teal and pink dots. Its rim,
// the robot's dark top mixed with the light, read (201, 223, 207), nearer
// to the lines than to yellow: the robot was dropped as a line-colored
// center. A center with no hue left is its four side blobs' center.
TEST(SceneRandomVenue, ACenterClippedWhiteIsItsFourDotsCenter) {
  const SceneScore s = venueScore({475, -2677, -1462, {247, 107, 180}, {30, 170, 140}, {241, 231, 71}, {58, 110, 189},
                                   {241, 75, 20}, {0.72, 0.83, 1.67}, 1.12, 1.16, 0.95, 2.19, 2.83, 2.09});
  EXPECT_EQ(s.recall(), 1.0);
  EXPECT_EQ(s.precision(), 1.0);
  EXPECT_EQ(s.idAccuracy(), 1.0);
}

// Moderate venue #570: under a warm cast (1.53, 0.81, 0.68) at gamma 1.59
// the teal dots of an amber robot read (30, 50, 35), a third of its center's
// brightness (189, 107, 59): taken for the robot's top, they left it no
// pattern, and one of them became a blue robot's center. A peak darker
// than a third of the center is still a marker where it lies nearer the
// center than the top between the dots in the ratio of brightnesses
// (hypothesis_search.cpp, darkerThanMarker). Held here at gamma 1.7, where
// six robots were lost so.
TEST(SceneRandomVenue, DarkDotsBesideABrightCenterAreMarkers) {
  const SceneScore s = venueScore({570, -1632, 1019, {246, 103, 179}, {45, 175, 129}, {244, 210, 48}, {85, 161, 232},
                                   {250, 104, 20}, {1.53, 0.81, 0.68}, 0.44, 1.70, 0.89, 1.66, -1.69, 0});
  EXPECT_EQ(s.recall(), 1.0);
  EXPECT_EQ(s.precision(), 1.0);
}

// The same venue at its own gamma: with the classes learned from every
// robot, where the center circle meets the halfway line a round blob of
// the crossing's false colors, (104, 67, 54), was taken for a ball. At a
// crossing a color no class explains is no ball (detector_balls.cpp).
TEST(SceneRandomVenue, ACrossingsFalseColorIsNoBall) {
  const SceneScore s = venueScore({570, -1632, 1019, {246, 103, 179}, {45, 175, 129}, {244, 210, 48}, {85, 161, 232},
                                   {250, 104, 20}, {1.53, 0.81, 0.68}, 0.44, 1.59, 0.89, 1.66, -1.69, 0});
  EXPECT_EQ(s.ballRecall(), 1.0);
  EXPECT_EQ(s.ballPrecision(), 1.0);
}

// Moderate venue #594: under a warm cast at gamma 0.65 the pink dots of a
// blue robot standing on a line read nearly white and made no peak; its
// yellow-green dot (236, 244, 160) became the center of a yellow robot of
// one side blob, the blue center its side. A center of at most one side
// blob nearer the frame's green or pink than its team's color is a dot
// (detector_colors.cpp, dropDotsTakenForCenters).
TEST(SceneRandomVenue, ADotIsNoCenterOfOneSideBlob) {
  const SceneScore s = venueScore({594, -940, -2297, {255, 139, 190}, {139, 206, 58}, {242, 227, 66}, {28, 56, 143},
                                   {255, 119, 20}, {1.49, 1.07, 0.74}, 0.57, 0.65, 1.06, 1.74, 1.02, 0});
  EXPECT_EQ(s.recall(), 1.0);
  EXPECT_EQ(s.precision(), 1.0);
}

// Extreme venue #366: under a warm cast (1.54, 1.09, 0.68) at exposure 1.21
// every lemon center clips in red and green, (251, 253, 145), and the
// sky-blue centers read gray, (167, 197, 182): no blob, the blue team
// unseen. The probe found seven of its full patterns, but the unseen
// team's split was learned from unclipped centers only, which were then
// the probed ones alone: one cluster. Where the seen team clipped in
// every center, the split is learned from every center (learnUnseenTeam).
TEST(SceneRandomVenue, ATeamClippedInEveryCenterStillSplitsFromTheUnseen) {
  const SceneScore s = venueScore({366, -3375, -1172, {234, 58, 165}, {132, 204, 64}, {244, 206, 44}, {85, 161, 232},
                                   {241, 73, 20}, {1.54, 1.09, 0.68}, 0.51, 1.13, 1.21, 1.68, -2.13, 1.57});
  EXPECT_GE(s.recall(), 15.0 / 16);
  EXPECT_EQ(s.precision(), 1.0);
}

// Extreme venue #640: under a warm cast (1.58, 0.98, 0.62) at exposure 1.3
// every lemon center clips, (251, 254, 165), and the lines clip with
// them: they read (229, 237, 222), as blue over green as the gray sky-blue
// centers (144, 163, 151) the probe found. The unseen team's check against
// the lines' cast failed: the blue team lost. Where the seen team clipped
// in every center, its own color is the reference (learnUnseenTeam).
TEST(SceneRandomVenue, WhereTheLinesClipTheSeenTeamTellsTheUnseenOne) {
  const SceneScore s = venueScore({640, -2577, -1490, {243, 90, 175}, {64, 181, 114}, {243, 219, 58}, {81, 154, 226},
                                   {250, 105, 20}, {1.58, 0.98, 0.62}, 0.45, 1.36, 1.30, 1.38, 2.89, 0});
  EXPECT_GE(s.recall(), 15.0 / 16);
  EXPECT_EQ(s.precision(), 1.0);
  EXPECT_EQ(s.idAccuracy(), 1.0);
}

// Moderate venue #329: a sun patch (2.13) over the ball under a cold cast
// lights it to (245, 186, 137) among darker carpet peaks, and the hypothesis
// search made a yellow robot of them, read as id 8, with a real yellow 8
// elsewhere in the frame: no ball, a false robot. One robot per team and id
// in a frame: the less sure goes, and its blobs to the ball (dropSecondIds).
TEST(SceneRandomVenue, ASecondRobotOfOneIdIsDroppedAndItsBallFound) {
  const SceneScore s = venueScore({329, -2241, 2240, {235, 59, 166}, {87, 189, 97}, {241, 236, 76}, {83, 158, 229},
                                   {242, 76, 20}, {0.85, 0.92, 1.51}, 0.70, 0.99, 0.87, 1.95, -0.12, 2.13});
  EXPECT_EQ(s.precision(), 1.0);
  EXPECT_EQ(s.ballRecall(), 1.0);
}

// Extreme venue #759: under tungsten (1.55, 1.02, 0.66) at saturation 1.23
// the sky-blue centers read (176, 224, 203) and did peak, but with the blue
// team unseen its class was the reference, the centers were dropped as
// implausible, and the probe for the unseen team took only centers that
// made no blob: the blue team lost. A peaked center no robot holds is
// probed as an unpeaked one (detector_unpeaked_centers.cpp).
TEST(SceneRandomVenue, ACenterThatPeakedButNoClassPlacedIsProbed) {
  const SceneScore s = venueScore({759, -3597, -1564, {242, 89, 175}, {81, 187, 102}, {240, 238, 78}, {89, 169, 239},
                                   {246, 91, 20}, {1.55, 1.02, 0.66}, 1.23, 0.91, 1.26, 1.90, -2.41, 0});
  EXPECT_GE(s.recall(), 15.0 / 16);
  EXPECT_EQ(s.precision(), 1.0);
  EXPECT_EQ(s.idAccuracy(), 1.0);
}

// Extreme venue #470 (moderate #470 at exposure 1.19 and uneven light
// 2.5): the probe found the gray sky-blue centers' full patterns, but two
// first-pass robots with centers of neither team's color, brown (129, 120,
// 83) and dark green (41, 48, 29), joined their cluster and pulled its
// mean below the lines' blue over green: the blue team was not learned
// (robots 0.438). The unseen team's color is its probed centers' alone
// (learnUnseenTeam).
TEST(SceneRandomVenue, AStrayCenterIsNoPartOfTheUnseenTeam) {
  const SceneScore s = venueScore({470, -1445, -2029, {238, 71, 169}, {52, 177, 123}, {241, 236, 75}, {87, 164, 235},
                                   {250, 103, 20}, {1.56, 0.94, 0.65}, 0.52, 1.50, 1.19, 2.46, 1.31, 1.92});
  EXPECT_GE(s.recall(), 14.0 / 16);
}

// Moderate venue #566: a sun patch (1.87) over the ball under a cold cast
// (0.88, 0.99, 1.48) clips it to (246, 241, 60). Its unclipped rim,
// (206, 213, 59), is the carpet mixed with the ball's own color as the
// light clipped it, a paler yellow than the amber centers': 47 from them,
// 12 from their mix with the lit carpet, beyond the class's reach (11). The
// rim may mix the ball's clip path too (marker_colored_ball.cpp).
TEST(SceneRandomVenue, ABallClippedInTheSunKeepsItsOwnPaleYellow) {
  const SceneScore s = venueScore({566, -3245, 724, {245, 100, 178}, {89, 190, 96}, {248, 183, 19}, {66, 126, 203},
                                   {254, 115, 20}, {0.88, 0.99, 1.48}, 1.23, 0.91, 1.15, 2.09, -0.42, 1.87});
  EXPECT_EQ(s.ballRecall(), 1.0);
  EXPECT_EQ(s.ballPrecision(), 1.0);
  EXPECT_EQ(s.recall(), 1.0);
}

// Extreme venue #690: a sun patch (1.82) over the ball under a warm cast
// (1.31, 0.99, 0.96) clips its red, but the blob's mean, blurred with the
// carpet, reads (236, 177, 99): no channel clipped, 14 from the amber
// centers, beyond their reach (13), so it was judged by its own color
// only. Any blob of a marker's color may be the ball's on its clip path
// mixed with the carpet around it, clipped or not (detector_balls.cpp).
TEST(SceneRandomVenue, ABallClippedInTheSunBlurredBelowTheTopIsStillTheBall) {
  const SceneScore s = venueScore({690, -956, 409, {239, 75, 171}, {61, 180, 117}, {246, 194, 31}, {46, 89, 171},
                                   {254, 116, 20}, {1.31, 0.99, 0.96}, 0.56, 1.32, 0.84, 1.27, 2.61, 1.82});
  EXPECT_EQ(s.ballRecall(), 1.0);
  EXPECT_EQ(s.ballPrecision(), 1.0);
}

// Moderate venue #325: a sun patch (1.91) over the ball under a magenta
// cast at saturation 0.51 reads (236, 160, 110), 35 from the amber
// centers. Its path as the light clips it starts from an orange that pale:
// the reference orange as this camera shows the markers (ColorMap), not
// the reference itself, whose blue stays far below (marker_colored_ball).
TEST(SceneRandomVenue, ADesaturatedBallClipsAlongItsOwnPath) {
  const SceneScore s = venueScore({325, -1064, 2017, {249, 116, 183}, {68, 183, 111}, {250, 168, 3}, {82, 154, 227},
                                   {246, 89, 20}, {1.10, 0.85, 1.21}, 0.51, 1.51, 1.03, 1.20, 2.68, 1.91});
  EXPECT_EQ(s.ballRecall(), 1.0);
  EXPECT_EQ(s.ballPrecision(), 1.0);
}

// Extreme venue #594 (moderate #594 at exposure 1.25): under the warm
// cast at gamma 0.65 the ball reads (236, 177, 125), nearer to orange than
// to the lemon centers by a small margin (confidence 0.15). Alone on the
// carpet, its hue between pink's and yellow's, the place vouches for it
// (detector_balls.cpp). And robot blue 9 by the image's edge keeps three
// of its four pale pink dots; the fourth, (238, 194, 184), read on the
// ball's plane, lies 133 mm from the robot's center, off its top, nearer
// to orange than to pink. On the top's plane it lies on the top, which
// hides whatever is below: no ball (insideRobot).
TEST(SceneRandomVenue, ABallOnlyJustOrangeAloneOnTheCarpetIsOneADotOnATopIsNot) {
  const SceneScore s = venueScore({594, -940, -2297, {255, 139, 190}, {139, 206, 58}, {242, 227, 66}, {28, 56, 143},
                                   {255, 119, 20}, {1.49, 1.07, 0.74}, 0.57, 0.65, 1.25, 2.24, 1.02, 0});
  EXPECT_EQ(s.ballRecall(), 1.0);
  EXPECT_EQ(s.ballPrecision(), 1.0);
  EXPECT_EQ(s.recall(), 1.0);
}

// Moderate venue #897: a sun patch (2.08) under a warm cast washes the
// pink dots of blue 3 toward white. One peaked weakly at (242, 237, 227),
// plainly nearer to the robot's green than to the frame's pink, and that
// label vetoed the four dots read from the frame, which split right: id 8
// for 3. Its red is clipped, so it may be redder than it shows, as a pink
// is: judged by what it may have been, it is pink (weak_sides.cpp).
TEST(SceneRandomVenue, AWeakDotClippedInRedMayBePink) {
  const SceneScore s = venueScore({897, -2476, 1600, {249, 114, 182}, {49, 176, 125}, {241, 234, 74}, {61, 116, 194},
                                   {251, 107, 20}, {1.56, 0.82, 0.65}, 0.65, 0.87, 1.10, 1.10, -2.19, 2.08});
  EXPECT_EQ(s.precision(), 1.0);
  EXPECT_EQ(s.idAccuracy(), 1.0);
}

// Moderate venue #1116: a cold cast at saturation 1.05 and gamma 0.61.
// The amber centers read (207, 171, 10), 134 from their dots, whose pinks
// and greens lie 65 apart: held to half the distance to its center
// (eq. 5.24), each robot's own split made one cluster, and seven of eight
// yellow robots read all pink or were lost. The frame's side classes split,
// and each dot lies clearly nearer to one of them (robot_identity.cpp).
TEST(SceneRandomVenue, AFarCenterColorLeavesTheSplitToTheFramesClasses) {
  const SceneScore s = venueScore({1116, -1435, 504, {252, 126, 186}, {66, 182, 113}, {249, 170, 6}, {88, 166, 237},
                                   {243, 79, 20}, {0.88, 0.97, 1.49}, 1.05, 0.61, 0.85, 1.16, -2.20, 0});
  EXPECT_EQ(s.recall(), 1.0);
  EXPECT_EQ(s.idAccuracy(), 1.0);
}

// Balls a sun patch clipped pale, each the only ball in view and found
// (marker_colored_ball.h, detector_balls.cpp):
// - moderate #1091 (1.87, warm cast, saturation 0.43): the ball read (245,
//   248, 205), nearest to the pale yellow centers, but the patch lit the
//   carpet around it to (157, 185, 144), within the centers' reach and
//   nearer to them than to the field class: taken for the ball's color, it
//   ran on beyond the ball's rim. Nearer to the ring's own carpet than to
//   the centers, it is carpet.
// - moderate #1006 (2.29, saturation 0.41) and #1020 (1.97, saturation
//   0.76): (239, 237, 180), nearest to the lines' white, and (250, 244,
//   149), nearest to yellow-green dots. Nearest to no marker's class, off
//   the markings, alone on the carpet, its color on the ball's own clip
//   path mixed with the carpet around it: the ball.
// - extreme #589 (1.97, exposure 1.36): the lit carpet, (191..227, 254,
//   139..163), between the carpet and the lemon centers, peaked beside the
//   ball: two false balls, six once the lit carpet no longer ran on beyond
//   their rims. A peak of its ring's own color is texture, and this
//   fallback gives one ball at most, the strongest.
TEST(SceneRandomVenue, BallsClippedPaleInTheSunAreFoundAlone) {
  const Venue venues[] = {
      {1091, -2134, 47, {240, 79, 172}, {67, 182, 113}, {242, 226, 65}, {33, 63, 150}, {252, 109, 20},
       {1.28, 1.14, 1.00}, 0.43, 0.87, 1.09, 1.84, -0.90, 1.87},
      {1006, -1021, -924, {242, 88, 174}, {58, 179, 119}, {243, 217, 55}, {79, 150, 223}, {254, 116, 20},
       {1.29, 0.89, 0.98}, 0.41, 1.53, 0.91, 1.00, -1.82, 2.29},
      {1020, -3751, 1174, {242, 88, 174}, {117, 199, 75}, {243, 217, 55}, {61, 117, 195}, {248, 98, 20},
       {1.50, 0.98, 0.72}, 0.76, 0.78, 1.07, 1.72, -0.85, 1.97},
      {589, -2545, 606, {253, 131, 187}, {50, 177, 125}, {241, 234, 74}, {29, 57, 145}, {247, 95, 20},
       {1.49, 1.06, 0.73}, 0.66, 1.33, 1.36, 1.46, -0.04, 1.97},
      // Extreme #296 (2.07) and #1020 (1.97): the ball clipped in red and
      // green over all of the 20 mm disc its rim was read in, (250, 254,
      // 167) and (253, 254, 179); its unclipped rim lies in its blurred edge
      // (Detector::Impl::readUnclipped). In #296 three lit-carpet peaks,
      // (197..233, 255, 130..154), each 4..8 from its ring's color, are
      // still no balls.
      {296, -1176, 2241, {251, 124, 185}, {136, 205, 61}, {240, 237, 77}, {38, 74, 159}, {252, 112, 20},
       {1.53, 1.17, 0.68}, 0.73, 1.28, 1.18, 2.94, -0.46, 2.07},
      {1020, -3751, 1174, {242, 88, 174}, {117, 199, 75}, {243, 217, 55}, {61, 117, 195}, {248, 98, 20},
       {1.50, 0.98, 0.72}, 0.76, 0.78, 1.27, 2.20, -0.85, 1.97}};
  for (const Venue& v : venues) {
    const SceneScore s = venueScore(v);
    EXPECT_EQ(s.ballRecall(), 1.0) << "venue " << v.seed << " at exposure " << v.exposure;
    EXPECT_EQ(s.ballPrecision(), 1.0) << "venue " << v.seed << " at exposure " << v.exposure;
  }
}

// Extreme venue #444 with its ball out of view: a blue robot not found in
// a sun patch (1.60) under a warm cast kept a yellow-green dot clipped pale,
// (231, 240, 124), nearest to the green class, on the ball's own clip path
// mixed with the carpet, and half its ring on the robot's top. Nearest to
// no marker, a ball's ring may show no robot's top.
TEST(SceneRandomVenue, APaleDotOfARobotNotFoundIsNoBall) {
  const SceneScore s = venueScore({444, -1542, 1776, {247, 109, 181}, {141, 207, 57}, {246, 197, 34}, {75, 142, 216},
                                   {248, 95, 20}, {1.32, 0.81, 0.94}, 0.84, 1.46, 1.25, 2.27, -0.36, 1.60},
                                  false);
  EXPECT_EQ(s.truth_balls, 0);
  EXPECT_EQ(s.balls_detected, 0);
}

// Under tungsten, with the ball out of view: the field's outer lines and a
// goal's walls. Extreme #849: a touch line 1.8 px wide drifts across the
// mosaic's phase, so its false color comes in orange and cyan stretches of
// about 100 mm; three orange ones, (188, 132, 63), became balls, the
// stretches 128 mm either way being cyan (streak_markings.h: a stretch in
// the same phase farther on stands for the line). Extreme #778: the corner
// of goal and touch line, its streak 28 mm from the touch line on the
// ball's plane and 15 on the ground. Moderate #470: a goal's back corner,
// 160 mm up, 70 mm beyond the wall on the ball's plane (detector_impl.h:
// a marking or wall is where the camera's ray meets it). Extreme #597: a
// touch line's stretch 22 px from the image's edge, which had faced only
// the fixed floor (the stretches the image shows are the reference).
// Extreme #676: a goal post's top, whose silhouette looks like a ball's
// (ABallAtRestOnTheFieldsCornerIsTheBall: on a marking only).
TEST(SceneRandomVenue, OuterLinesAndGoalCornersAreNoBall) {
  const Venue venues[] = {
      {849, -3122, -1332, {247, 109, 181}, {73, 184, 108}, {248, 179, 15}, {31, 61, 148}, {242, 78, 20},
       {1.60, 0.82, 0.60}, 0.99, 1.56, 1.30, 1.35, -2.87, 1.95},
      {778, -1244, 777, {247, 110, 181}, {75, 185, 106}, {242, 227, 66}, {44, 85, 168}, {246, 89, 20},
       {1.56, 0.85, 0.65}, 1.23, 1.43, 1.34, 2.67, -0.56, 1.82},
      {470, -1445, -2029, {238, 71, 169}, {52, 177, 123}, {241, 236, 75}, {87, 164, 235}, {250, 103, 20},
       {1.56, 0.94, 0.65}, 0.52, 1.50, 1.03, 1.88, 1.31, 1.92},
      {597, -1289, 1941, {243, 93, 176}, {42, 174, 131}, {245, 205, 43}, {29, 56, 144}, {247, 95, 20},
       {1.51, 0.86, 0.71}, 0.78, 1.51, 1.12, 1.53, -1.44, 0},
      {676, -3690, -1926, {245, 100, 178}, {109, 196, 81}, {248, 178, 14}, {25, 50, 139}, {248, 97, 20},
       {1.57, 1.13, 0.63}, 0.96, 1.35, 1.13, 1.83, 2.48, 1.75},
  };
  for (const Venue& v : venues) {
    const SceneScore s = venueScore(v, false);
    EXPECT_EQ(s.truth_balls, 0) << v.seed;
    EXPECT_EQ(s.balls_detected, 0) << v.seed;
  }
}

// A ball at rest on the field's corner (extremes #32 and #44 with the ball
// moved there): the lines kept the round score from peaking, so only the
// streak pass found it, (245, 97, 48) and (234, 90, 16), and an untracked
// streak where markings meet was dropped whatever its color. One that
// shows a whole ball's silhouette in the ball's colors is the ball.
TEST(SceneRandomVenue, ABallAtRestOnTheFieldsCornerIsTheBall) {
  const Venue venues[] = {
      {32, -4513, -3008, {242, 89, 175}, {49, 176, 126}, {245, 201, 38}, {24, 47, 136}, {242, 76, 20},
       {1.53, 0.89, 0.69}, 0.67, 1.50, 1.10, 2.44, -2.51, 0},
      {44, -4508, -2985, {255, 139, 190}, {131, 204, 64}, {245, 201, 39}, {21, 41, 131}, {245, 85, 20},
       {1.23, 1.02, 1.05}, 1.18, 0.78, 0.94, 1.06, -2.41, 0},
  };
  for (const Venue& v : venues) {
    const SceneScore s = venueScore(v);
    EXPECT_EQ(s.truth_balls, 1) << v.seed;
    EXPECT_EQ(s.balls_matched, 1) << v.seed;
    EXPECT_EQ(s.balls_detected, 1) << v.seed;
  }
}

// Robots whose center made no blob (detector_unpeaked_centers.cpp), their
// dots washed out under an over-exposed cast. Extreme #176 (tungsten,
// exposure 1.34): a blue robot's pink dot, (240, 184, 186), scored below
// the blob threshold as a disc and peaked only as a fast-ball streak;
// beside a green and a pink blob it fills the pattern's third side.
// Extreme #475 (a sun patch of 2.09 under a cold cast): a yellow robot's
// center clipped white, (252, 253, 249), beside three teal dots, one a
// streak; no hue is left to place it, so its three sides are judged as a
// full pattern's four are (the brighter team).
TEST(SceneRandomVenue, WashedDotsThatPeakedAsStreaksAreSides) {
  const SceneScore washed_pink = venueScore({176, -2861, -924, {241, 83, 173}, {138, 206, 59}, {250, 167, 2},
                                             {68, 130, 206}, {241, 72, 20}, {1.57, 1.11, 0.63}, 0.60, 0.71,
                                             1.34, 2.27, 0.80, 0});
  EXPECT_GE(washed_pink.matched, 14);  // 13 without the streak as a side
  EXPECT_EQ(washed_pink.precision(), 1.0);
  EXPECT_EQ(washed_pink.idAccuracy(), 1.0);
  const SceneScore white_center = venueScore({475, -2677, -1462, {247, 107, 180}, {30, 170, 140}, {241, 231, 71},
                                              {58, 110, 189}, {241, 75, 20}, {0.72, 0.83, 1.67}, 1.12, 1.16,
                                              1.06, 2.98, 2.83, 2.09});
  EXPECT_EQ(white_center.recall(), 1.0);
  EXPECT_EQ(white_center.precision(), 1.0);
  EXPECT_EQ(white_center.idAccuracy(), 1.0);
}

// Extreme venue #40 (exposure 1.38 under 2.3 : 1 uneven light at
// saturation 0.43): of four robots lost, three peaked as one green blob
// each and one as two, their centers and pinks washed toward the lines'
// white. Around a lone green or pink blob the center is the brightest
// place on the ring of the side distance (detector_lone_sides.cpp).
TEST(SceneRandomVenue, ARobotOfWhichOnlyOneDotPeakedIsFound) {
  const SceneScore s = venueScore({40, -3471, 678, {246, 105, 180}, {44, 175, 129}, {244, 207, 45}, {88, 166, 237},
                                   {242, 75, 20}, {1.19, 1.15, 1.10}, 0.43, 0.88, 1.38, 2.33, -2.33, 0});
  EXPECT_GE(s.matched, 14);  // 11 without
  EXPECT_EQ(s.precision(), 1.0);
  EXPECT_EQ(s.idAccuracy(), 1.0);
}

// Moderate venue #994 with the ball out of view: a sun patch of 2.1 under
// a cold cast lights the carpet near clipping, and its texture peaks in
// green and pink. Around such a peak the ring is bright all round: no
// robot's dark top, so no robot of a lone side (one false robot of the
// first search stays, open; the lone-side stage without its dark-top test
// made a second).
TEST(SceneRandomVenue, ALoneSideOnSunLitCarpetMakesNoRobot) {
  const SceneScore s = venueScore({994, -676, 1344, {252, 129, 187}, {61, 180, 117}, {250, 166, 1}, {70, 133, 209},
                                   {254, 115, 20}, {0.75, 1.10, 1.64}, 0.90, 1.53, 1.14, 1.44, 0.10, 2.10},
                                  false);
  EXPECT_EQ(s.recall(), 1.0);
  EXPECT_LE(s.detected - s.matched, 1);
}

// A ball's ring is the carpet where it looks like the carpet beyond the
// top of a robot the ball would be the center of (carpetAroundBall), in
// whatever light the ball has. Extreme #309: a red ball on a carpet so dark
// (gamma 1.50, exposure 0.92) that the ring is darker than a robot's top
// may be beside the ball. Extreme #994: a sun patch (2.10) under a cold
// cast clips the carpet around a pale ball to the sky-blue centers' color.
// Extreme #1092: a sun patch (2.14) at exposure 1.40 lights the carpet
// toward the blue centers' color too. Moderate #1092 with its ball out of
// view: a pink side dot of a robot not found, its ring on the robot's top,
// the ring beyond crossing that top and a neighbour's, is no ball (the
// carpet beyond must be what most of that ring shows).
TEST(SceneRandomVenue, TheCarpetBeyondARobotsReachTellsTheBallsRing) {
  const Venue venues[] = {
      {309, -2107, -1834, {243, 90, 175}, {128, 203, 66}, {248, 180, 16}, {22, 43, 133}, {249, 100, 20},
       {1.54, 0.80, 0.67}, 0.58, 1.50, 0.92, 2.46, 1.66, 0},
      {994, -676, 1344, {252, 129, 187}, {61, 180, 117}, {250, 166, 1}, {70, 133, 209}, {254, 115, 20},
       {0.75, 1.10, 1.64}, 0.90, 1.53, 1.39, 1.74, 0.10, 2.10},
      {1092, -1639, 155, {230, 41, 160}, {101, 194, 87}, {249, 172, 8}, {87, 165, 235}, {242, 78, 20},
       {1.06, 1.00, 1.26}, 0.63, 0.74, 1.40, 2.42, 1.40, 2.14}};
  for (const Venue& v : venues) {
    const SceneScore s = venueScore(v);
    EXPECT_EQ(s.ballRecall(), 1.0) << "venue " << v.seed;
    EXPECT_EQ(s.ballPrecision(), 1.0) << "venue " << v.seed;
  }
  const SceneScore side = venueScore({1092, -1639, 155, {230, 41, 160}, {101, 194, 87}, {249, 172, 8}, {87, 165, 235},
                                      {242, 78, 20}, {1.06, 1.00, 1.26}, 0.63, 0.74, 1.15, 1.85, 1.40, 2.14},
                                     false);
  EXPECT_EQ(side.truth_balls, 0);
  EXPECT_EQ(side.balls_detected, 0);
}

// Extreme #1006: a sun patch (2.29) at saturation 0.41 clips the ball to
// (237, 238, 193), nearest to the lines' white, beside a robot whose lit
// body, (108, 104, 73), took two of its 24 ring samples. A ball nearest to
// no marker needed carpet all round; what the ring must not show is a
// robot's top (too dark for carpet; APaleDotOfARobotNotFoundIsNoBall).
TEST(SceneRandomVenue, APaleBallBesideARobotsBodyIsTheBall) {
  const SceneScore s = venueScore({1006, -1021, -924, {242, 88, 174}, {58, 179, 119}, {243, 217, 55}, {79, 150, 223},
                                   {254, 116, 20}, {1.29, 0.89, 0.98}, 0.41, 1.53, 0.99, 1.00, -1.82, 2.29});
  EXPECT_EQ(s.ballRecall(), 1.0);
  EXPECT_EQ(s.ballPrecision(), 1.0);
}

// A venue YAML the script wrote (DV_VENUE=PATH), scored as the script
// scores it, at half resolution: with DV_MISSES=1 (and DV_DUMP=DIR) what
// it lost and the blobs around each. A tool for looking, not a bar.
TEST(SceneRandomVenue, DISABLED_AVenueFileWithItsMisses) {
  const char* path = std::getenv("DV_VENUE");
  if (!path) GTEST_SKIP() << "DV_VENUE names no venue YAML";
  std::ifstream in(path);
  ASSERT_TRUE(in) << path;
  std::stringstream text;
  text << in.rdbuf();
  SceneSpec s = sceneFromYaml(text.str(), path);
  halveResolution(s);
  SceneScore sc;
  score(s, 1, true, sc);
  std::printf("%s\n", sc.summary(path).c_str());
}

}  // namespace
}  // namespace dv
