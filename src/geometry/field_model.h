#pragma once
// The SSL field (SSL_GeometryFieldSize): scalar dimensions plus the painted
// line segments and arcs, in millimetres in the SSL field frame.
#include <algorithm>
#include <optional>
#include <string>
#include <vector>

#include "core/units.h"

namespace dv {

// Values of SSL_FieldShapeType.
enum class FieldShape {
  Undefined = 0,
  CenterCircle = 1,
  TopTouchLine = 2,
  BottomTouchLine = 3,
  LeftGoalLine = 4,
  RightGoalLine = 5,
  HalfwayLine = 6,
  CenterLine = 7,
  LeftPenaltyStretch = 8,
  RightPenaltyStretch = 9,
  LeftFieldLeftPenaltyStretch = 10,
  LeftFieldRightPenaltyStretch = 11,
  RightFieldLeftPenaltyStretch = 12,
  RightFieldRightPenaltyStretch = 13,
};

struct FieldLine {
  std::string name;
  FieldMm p1, p2;  // on the line's center line
  double thickness = 10;
  FieldShape type = FieldShape::Undefined;
};

struct FieldArc {
  std::string name;
  FieldMm center;
  double radius = 0;  // to the line center
  double a1 = 0, a2 = 0;  // rad, counter-clockwise from +x
  double thickness = 10;
  FieldShape type = FieldShape::Undefined;

  // The angle it spans counter-clockwise from a1, in (0, 2 pi]: a2 <= a1
  // wraps once, and anything from 2 pi on is the whole circle (a geometry
  // packet's float 2 pi, 6.28318548, lies just above the double).
  double span() const {
    double s = a2 - a1;
    if (s <= 0) s += 2 * kPi;
    return std::min(s, 2 * kPi);
  }
};

// Distance (mm) from p to the segment ab.
double distanceToSegment(FieldMm p, FieldMm a, FieldMm b);

// An axis-parallel rectangle on the field.
struct FieldRect {
  double x_min = 0, x_max = 0, y_min = 0, y_max = 0;
  bool contains(FieldMm p) const { return p.x >= x_min && p.x <= x_max && p.y >= y_min && p.y <= y_max; }
};

struct FieldModel {
  int field_length = 9000;
  int field_width = 6000;
  int goal_width = 1000;
  int goal_depth = 180;
  int boundary_width = 300;
  int boundary_width_goal_line = 300;
  int penalty_area_depth = 1000;
  int penalty_area_width = 2000;
  int center_circle_radius = 500;
  int line_thickness = 10;
  int goal_center_to_penalty_mark = 6000;
  int goal_height = 160;
  double ball_radius = 21.5;
  double max_robot_radius = 90;
  int goal_substitution_area_width = 0;
  std::vector<FieldLine> lines;
  std::vector<FieldArc> arcs;

  // Dimensions as the league's rules publish them, with lines generated.
  static FieldModel divisionA();
  static FieldModel divisionB();

  // Replaces lines and arcs by the standard markings for the current scalar
  // dimensions, in the order and naming SSL-Vision publishes them.
  void generateMarkings();

  // The playing area plus the boundary up to the walls.
  FieldRect withBoundary() const;

  // Distance (mm) from p to the nearest marking's center line (a line or
  // an arc); infinity where there are none.
  double distanceToMarkings(FieldMm p) const;
  // How many markings (lines and arcs) pass within `reach` mm of p: two or
  // more where they meet.
  int markingsWithin(FieldMm p, double reach) const;

  // The goals' walls (the rules: 20 mm thick; goal_depth from the goal
  // line's outer edge to the back wall's inner face): the distance (mm)
  // from p to the nearest wall's center line.
  static constexpr double kGoalWallThickness = 20;
  double distanceToGoalWalls(FieldMm p) const;
  // The part of the field a camera covers in SSL-Vision's default layout
  // (ids count along +y first, then +x). Empty for unsupported totals.
  std::optional<FieldRect> cameraRegion(unsigned camera_id, unsigned num_cameras) const;
};

}  // namespace dv
