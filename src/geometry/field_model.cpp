#include "geometry/field_model.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace dv {

FieldModel FieldModel::divisionA() {
  FieldModel f;
  f.field_length = 12000;
  f.field_width = 9000;
  f.goal_width = 1800;
  f.boundary_width_goal_line = 600;
  f.penalty_area_depth = 1800;
  f.penalty_area_width = 3600;
  f.goal_center_to_penalty_mark = 8000;
  f.goal_substitution_area_width = 300;
  f.generateMarkings();
  return f;
}

FieldModel FieldModel::divisionB() {
  FieldModel f;  // the member defaults are Division B
  f.generateMarkings();
  return f;
}

void FieldModel::generateMarkings() {
  const double l = field_length / 2.0, w = field_width / 2.0;
  const double xp = l - penalty_area_depth, yp = penalty_area_width / 2.0;
  const double t = line_thickness;
  using S = FieldShape;
  lines = {
      {"TopTouchLine", {-l, w}, {l, w}, t, S::TopTouchLine},
      {"BottomTouchLine", {-l, -w}, {l, -w}, t, S::BottomTouchLine},
      {"LeftGoalLine", {-l, -w}, {-l, w}, t, S::LeftGoalLine},
      {"RightGoalLine", {l, -w}, {l, w}, t, S::RightGoalLine},
      {"HalfwayLine", {0, -w}, {0, w}, t, S::HalfwayLine},
      {"LeftPenaltyStretch", {-xp, -yp}, {-xp, yp}, t, S::LeftPenaltyStretch},
      {"RightPenaltyStretch", {xp, -yp}, {xp, yp}, t, S::RightPenaltyStretch},
      {"LeftFieldLeftPenaltyStretch", {-l, -yp}, {-xp, -yp}, t, S::LeftFieldLeftPenaltyStretch},
      {"LeftFieldRightPenaltyStretch", {-l, yp}, {-xp, yp}, t, S::LeftFieldRightPenaltyStretch},
      {"RightFieldRightPenaltyStretch", {l, -yp}, {xp, -yp}, t, S::RightFieldRightPenaltyStretch},
      {"RightFieldLeftPenaltyStretch", {l, yp}, {xp, yp}, t, S::RightFieldLeftPenaltyStretch},
      {"CenterLine", {-l, 0}, {l, 0}, t, S::CenterLine},
  };
  // SSL-Vision draws the center circle 10 mm wide whatever line_thickness is.
  arcs = {{"CenterCircle", {0, 0}, double(center_circle_radius), 0, 2 * kPi, 10, S::CenterCircle}};
}

FieldRect FieldModel::withBoundary() const {
  const double x = field_length / 2.0 + boundary_width_goal_line;
  const double y = field_width / 2.0 + boundary_width;
  return {-x, x, -y, y};
}

double distanceToSegment(FieldMm p, FieldMm a, FieldMm b) {
  const double dx = b.x - a.x, dy = b.y - a.y, len2 = dx * dx + dy * dy;
  const double t = len2 > 0 ? std::clamp(((p.x - a.x) * dx + (p.y - a.y) * dy) / len2, 0.0, 1.0) : 0.0;
  return std::hypot(p.x - a.x - t * dx, p.y - a.y - t * dy);
}

namespace {

// On the arc's span: the distance to its circle; else to its nearer end.
double distanceToArc(FieldMm p, const FieldArc& a) {
  double angle = std::atan2(p.y - a.center.y, p.x - a.center.x) - a.a1;
  angle -= 2 * kPi * std::floor(angle / (2 * kPi));
  if (angle <= a.span()) return std::abs(std::hypot(p.x - a.center.x, p.y - a.center.y) - a.radius);
  double best = std::numeric_limits<double>::infinity();
  for (double e : {a.a1, a.a2})
    best = std::min(best, std::hypot(p.x - a.center.x - a.radius * std::cos(e),
                                     p.y - a.center.y - a.radius * std::sin(e)));
  return best;
}

}  // namespace

double FieldModel::distanceToMarkings(FieldMm p) const {
  double best = std::numeric_limits<double>::infinity();
  for (const FieldLine& l : lines) best = std::min(best, distanceToSegment(p, l.p1, l.p2));
  for (const FieldArc& a : arcs) best = std::min(best, distanceToArc(p, a));
  return best;
}

int FieldModel::markingsWithin(FieldMm p, double reach) const {
  int n = 0;
  for (const FieldLine& l : lines) n += distanceToSegment(p, l.p1, l.p2) < reach;
  for (const FieldArc& a : arcs) n += distanceToArc(p, a) < reach;
  return n;
}

double FieldModel::distanceToGoalWalls(FieldMm p) const {
  const double front = field_length / 2.0 + line_thickness / 2.0, back = front + goal_depth;
  const double half = kGoalWallThickness / 2, gw = goal_width / 2.0 + half;
  auto segment = [&](FieldMm a, FieldMm b) { return distanceToSegment(p, a, b); };
  double best = std::numeric_limits<double>::infinity();
  for (double sx : {-1.0, 1.0})
    best = std::min({best, segment({sx * (back + half), -gw}, {sx * (back + half), gw}),
                     segment({sx * front, gw}, {sx * (back + half), gw}),
                     segment({sx * front, -gw}, {sx * (back + half), -gw})});
  return best;
}

std::optional<FieldRect> FieldModel::cameraRegion(unsigned camera_id, unsigned num_cameras) const {
  unsigned nx = 0, ny = 0;
  switch (num_cameras) {
    case 1: nx = 1, ny = 1; break;
    case 2: nx = 2, ny = 1; break;
    case 4: nx = 2, ny = 2; break;
    case 6: nx = 3, ny = 2; break;
    case 8: nx = 4, ny = 2; break;
    default: return std::nullopt;
  }
  if (camera_id >= num_cameras) return std::nullopt;
  const double dx = double(field_length) / nx, dy = double(field_width) / ny;
  const double x0 = -field_length / 2.0 + (camera_id / ny) * dx;
  const double y0 = -field_width / 2.0 + (camera_id % ny) * dy;
  return FieldRect{x0, x0 + dx, y0, y0 + dy};
}

}  // namespace dv
