// Distances to what the field geometry knows is painted or built thin:
// the detector takes no untracked fast-ball streak there.
#include <gtest/gtest.h>

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
