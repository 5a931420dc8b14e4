// Pattern fit, rule-shape tests and the color clustering used by detection.
#include <gtest/gtest.h>

#include <cmath>

#include "detection/color_classes.h"
#include "detection/pattern_fit.h"

namespace dv {
namespace {

TEST(DetectionFit, RecoversPoseExactlyAndScoresOffsets) {
  const FieldMm pos{1234.5, -678.9};
  const double ori = 2.7;
  FieldMm pts[5];
  int slots[5] = {0, 1, 2, 3, 4};
  for (int s = 0; s < 5; ++s) pts[s] = slotPosition(pos, ori, s);
  PatternPose p = fitPattern(pts, slots, 5, 10);
  EXPECT_NEAR(p.position.x, pos.x, 1e-9);
  EXPECT_NEAR(p.position.y, pos.y, 1e-9);
  EXPECT_NEAR(p.orientation, ori, 1e-12);
  EXPECT_NEAR(p.score, 1.0, 1e-12);
  // Two blobs are enough for a pose (tracking), any two slots.
  int two[2] = {2, 4};
  FieldMm two_pts[2] = {pts[2], pts[4]};
  p = fitPattern(two_pts, two, 2, 10);
  EXPECT_NEAR(p.position.x, pos.x, 1e-9);
  EXPECT_NEAR(p.orientation, ori, 1e-12);
  // One blob 12.5 mm off: its residual after the least-squares fit is
  // 12.5 * (1 - 1/5) = 10 mm (the others absorb a fifth), giving 0.5.
  pts[3].x += 12.5;
  p = fitPattern(pts, slots, 5, 10);
  EXPECT_NEAR(p.score, 0.5, 0.05);
  pts[3].x += 40;
  EXPECT_LT(fitPattern(pts, slots, 5, 10).score, 0.1);
}

// Where a tilted camera stretches the field along its viewing ray, a blob
// off its slot along the ray counts that much less; across it, as before.
TEST(DetectionFit, ToleranceStretchedAlongTheViewingRay) {
  FieldMm pts[5];
  int slots[5] = {0, 1, 2, 3, 4};
  for (int s = 0; s < 5; ++s) pts[s] = slotPosition({500, 200}, 0.4, s);
  const double ray[2] = {0.6, 0.8};
  FitTolerance tol{10, ray[0], ray[1], 2};
  FieldMm along[5], across[5];
  for (int s = 0; s < 5; ++s) along[s] = across[s] = pts[s];
  along[3] = {pts[3].x + 25 * ray[0], pts[3].y + 25 * ray[1]};
  across[3] = {pts[3].x - 12.5 * ray[1], pts[3].y + 12.5 * ray[0]};
  // 25 mm along at stretch 2 scores as 12.5 mm off does when round (0.5,
  // see above); across, the residuals the fit spreads over the other
  // blobs are all that change.
  EXPECT_NEAR(fitPattern(along, slots, 5, tol).score, 0.5, 0.05);
  EXPECT_LT(fitPattern(along, slots, 5, 10).score, 0.25);
  EXPECT_NEAR(fitPattern(across, slots, 5, tol).score, fitPattern(across, slots, 5, 10).score, 0.01);
  EXPECT_LT(fitPattern(across, slots, 5, tol).score, 0.7);
  // Stretch 1 is the plain score.
  tol.stretch = 1;
  EXPECT_EQ(fitPattern(along, slots, 5, tol).score, fitPattern(along, slots, 5, 10).score);
}

TEST(DetectionFit, WrongSlotOrderScoresBadly) {
  FieldMm pts[5];
  for (int s = 0; s < 5; ++s) pts[s] = slotPosition({0, 0}, 0.3, s);
  // A cyclic shift of the side slots is a rotation by 66..114 degrees: the
  // pattern's uneven angles leave residuals of ~20 mm, far below the truth.
  int shifted[5] = {0, 2, 3, 4, 1};
  EXPECT_LT(fitPattern(pts, shifted, 5, 10).score, 0.3);
  int mirrored[5] = {0, 4, 3, 2, 1};
  EXPECT_LT(fitPattern(pts, mirrored, 5, 10).score, 0.1);
}

TEST(DetectionFit, RobotTopsOverlapByTheRuleShape) {
  // Round backs: 170 mm is the closest two tops can be.
  EXPECT_FALSE(robotTopsOverlap({0, 0}, 0, {180, 0}, 0));
  EXPECT_TRUE(robotTopsOverlap({0, 0}, kPi, {150, 0}, 0));  // back to back
  // Flat fronts facing each other may come to 110 mm.
  EXPECT_FALSE(robotTopsOverlap({0, 0}, 0, {120, 0}, kPi));
  EXPECT_TRUE(robotTopsOverlap({0, 0}, 0, {100, 0}, kPi));
  // Front to back: 55 + 85 = 140.
  EXPECT_FALSE(robotTopsOverlap({0, 0}, 0, {145, 0}, 0));
  EXPECT_TRUE(robotTopsOverlap({0, 0}, 0, {130, 0}, 0));
  // Rotation of the frame does not matter.
  EXPECT_FALSE(robotTopsOverlap({0, 0}, kPi / 2, {0, 145}, kPi / 2));
  EXPECT_TRUE(robotTopsOverlap({0, 0}, kPi / 2, {0, 130}, kPi / 2));
}

TEST(DetectionFit, DistanceToRobotTop) {
  EXPECT_DOUBLE_EQ(distanceToRobotTop({10, 10}, {0, 0}, 0), 0);
  EXPECT_NEAR(distanceToRobotTop({60, 0}, {0, 0}, 0), 5, 1e-9);      // front
  EXPECT_NEAR(distanceToRobotTop({-100, 0}, {0, 0}, 0), 15, 1e-9);   // back
  EXPECT_NEAR(distanceToRobotTop({0, 60}, {0, 0}, kPi / 2), 5, 1e-9);
  EXPECT_NEAR(minBallOutsideDistance(21.5), 10.575, 0.01);
}

TEST(DetectionColor, TwoMeansFindsTwoClustersOrOne) {
  const ColorVec yellow = colorFeature(230, 210, 40), blue = colorFeature(40, 80, 200);
  const ColorVec green = colorFeature(60, 200, 80), pink = colorFeature(240, 90, 180);
  const ColorVec prior[2] = {yellow, blue};
  const ColorVec ext[2] = {green, pink};
  ColorVec s[6] = {colorFeature(200, 220, 80), colorFeature(190, 215, 70), colorFeature(30, 90, 250),
                   colorFeature(35, 95, 255), colorFeature(205, 225, 85), colorFeature(25, 85, 245)};
  uint8_t labels[6];
  auto r = twoMeans(s, 6, prior, ext, 2, labels);
  EXPECT_TRUE(r.separated);
  EXPECT_EQ(labels[0], 0);
  EXPECT_EQ(labels[1], 0);
  EXPECT_EQ(labels[2], 1);
  EXPECT_EQ(labels[3], 1);
  EXPECT_EQ(labels[4], 0);
  EXPECT_EQ(labels[5], 1);
  // Only yellow robots, white balance shifted towards blue: one cluster,
  // and it is yellow.
  ColorVec only[3] = {colorFeature(172, 200, 58), colorFeature(165, 195, 60), colorFeature(175, 205, 55)};
  r = twoMeans(only, 3, prior, ext, 2, labels);
  EXPECT_FALSE(r.separated);
  EXPECT_EQ(labels[0], 0);
  EXPECT_EQ(labels[2], 0);
  EXPECT_EQ(r.count[1], 0);
}

TEST(DetectionColor, ColorMapCarriesAShiftToUnseenClasses) {
  // Observed = a desaturated camera: each chroma pulled halfway to gray.
  const ColorVec ref[4] = {colorFeature(230, 210, 40), colorFeature(40, 80, 200),
                           colorFeature(60, 200, 80), colorFeature(240, 90, 180)};
  ColorVec seen[4];
  for (int i = 0; i < 4; ++i)
    for (int k = 0; k < 3; ++k) seen[i].c[k] = 0.5f * ref[i].c[k] + 0.5f * 97.f;
  ColorMap map;
  EXPECT_FALSE(map.valid());
  map.fit(ref, seen, 4);
  ASSERT_TRUE(map.valid());
  const ColorVec orange = colorFeature(255, 120, 20);
  const ColorVec mapped = map.apply(orange);
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(mapped.c[k], 0.5f * orange.c[k] + 0.5f * 97.f, 3.0);
  ColorClass cls{orange, orange};
  cls.update(mapped, 0.7f, 0.1f);  // eq. 5.25
  EXPECT_NEAR(cls.color.c[0], 0.8f * orange.c[0] + 0.2f * mapped.c[0], 1e-3);
}

}  // namespace
}  // namespace dv
