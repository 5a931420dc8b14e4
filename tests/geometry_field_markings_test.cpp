// Distances to what the field geometry knows is painted or built thin:
// the detector takes no untracked fast-ball streak there.
#include <gtest/gtest.h>

#include <cmath>

#include "geometry/field_model.h"

namespace dv {
namespace {

TEST(FieldMarkings, DistanceToTheNearestLineOrArc) {
  const FieldModel f = FieldModel::divisionB();
  EXPECT_NEAR(f.distanceToMarkings({0, 0}), 0, 1e-9);                  // on the halfway line
  EXPECT_NEAR(f.distanceToMarkings({-2000, 2990}), 10, 1e-9);          // 10 mm inside the touch line
  EXPECT_NEAR(f.distanceToMarkings({-300, 400}), 0, 1e-9);             // on the center circle (radius 500)
  EXPECT_NEAR(f.distanceToMarkings({-1000, 1500}), 1000, 1e-9);        // midway: the halfway line is nearest
  EXPECT_NEAR(f.distanceToMarkings({-4000, -2000}), 500, 1e-9);        // the goal line
}

// Where markings meet: a ball's reach of two or more (the detector judges a
// streak there as it judges one in the lines' own color).
TEST(FieldMarkings, MarkingsMeetAtCrossingsCornersAndTheCenter) {
  const FieldModel f = FieldModel::divisionB();
  const double reach = 26.5;  // a ball's radius and half a line
  EXPECT_EQ(f.markingsWithin({-3491, 6}, reach), 2);       // center line and penalty stretch
  EXPECT_EQ(f.markingsWithin({-4490, -2990}, reach), 2);   // the field's corner
  EXPECT_GE(f.markingsWithin({0, 0}, reach), 2);           // halfway and center lines
  EXPECT_EQ(f.markingsWithin({-2250, 5}, reach), 1);       // on the center line alone
  EXPECT_EQ(f.markingsWithin({-300, 400}, reach), 1);      // on the center circle alone
  EXPECT_EQ(f.markingsWithin({-1000, 1500}, reach), 0);    // on the carpet
}

// A geometry packet carries the center circle's a2 as a float, 6.28318548,
// just above the double 2 pi: still the whole circle (read modulo 2 pi it
// spanned 2e-7 rad, and the center circle was a point at its a1).
TEST(FieldMarkings, AFloatFullCircleIsTheWholeCircle) {
  FieldModel f = FieldModel::divisionB();
  for (FieldArc& a : f.arcs) a.a2 = static_cast<float>(a.a2);
  EXPECT_NEAR(f.distanceToMarkings({-353, -353}), 500 - std::hypot(353, 353), 1e-6);
  EXPECT_NEAR(f.distanceToMarkings({-300, -400 * 1.04}), std::hypot(300, 416) - 500, 1e-6);
  FieldArc half{"", {0, 0}, 500, 0, kPi};
  EXPECT_NEAR(half.span(), kPi, 1e-12);
  half.a2 = -kPi / 2;  // wraps once: three quarters
  EXPECT_NEAR(half.span(), 1.5 * kPi, 1e-12);
}

TEST(FieldMarkings, DistanceToTheGoalWallsCenterLines) {
  const FieldModel f = FieldModel::divisionB();
  const double front = f.field_length / 2.0 + f.line_thickness / 2.0;
  const double side = f.goal_width / 2.0 + FieldModel::kGoalWallThickness / 2;
  EXPECT_NEAR(f.distanceToGoalWalls({-(front + 50), side}), 0, 1e-9);  // in the side wall
  EXPECT_NEAR(f.distanceToGoalWalls({front + 50, -side + 30}), 30, 1e-9);
  // In the goal, 90 mm behind the line: the back wall's center line is 100 mm on.
  EXPECT_NEAR(f.distanceToGoalWalls({-(front + 90), 0}), f.goal_depth - 90 + 10, 1e-9);
  EXPECT_GT(f.distanceToGoalWalls({0, 0}), 4000);
}

TEST(FieldMarkings, SegmentDistanceEndsAndDegenerate) {
  EXPECT_NEAR(distanceToSegment({0, 5}, {-10, 0}, {10, 0}), 5, 1e-12);
  EXPECT_NEAR(distanceToSegment({13, 4}, {-10, 0}, {10, 0}), 5, 1e-12);  // beyond an end
  EXPECT_NEAR(distanceToSegment({3, 4}, {0, 0}, {0, 0}), 5, 1e-12);      // a point
}

}  // namespace
}  // namespace dv
