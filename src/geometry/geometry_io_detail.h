#pragma once
// What geometry_io.cpp and geometry_yaml.cpp share: the field's scalar
// dimensions by their proto names, the preset a field's missing dimensions
// come from, and how numbers are written. Private to src/geometry.
#include <string>

#include "geometry/field_model.h"

namespace dv {
namespace geometry_io_detail {

// ---- the field's scalar dimensions, by their proto names ----

struct IntDimension {
  const char* name;
  int FieldModel::*member;
};
inline constexpr IntDimension kIntDimensions[] = {
    {"field_length", &FieldModel::field_length},
    {"field_width", &FieldModel::field_width},
    {"goal_width", &FieldModel::goal_width},
    {"goal_depth", &FieldModel::goal_depth},
    {"boundary_width", &FieldModel::boundary_width},
    {"boundary_width_goal_line", &FieldModel::boundary_width_goal_line},
    {"penalty_area_depth", &FieldModel::penalty_area_depth},
    {"penalty_area_width", &FieldModel::penalty_area_width},
    {"center_circle_radius", &FieldModel::center_circle_radius},
    {"line_thickness", &FieldModel::line_thickness},
    {"goal_center_to_penalty_mark", &FieldModel::goal_center_to_penalty_mark},
    {"goal_height", &FieldModel::goal_height},
    {"goal_substitution_area_width", &FieldModel::goal_substitution_area_width},
};
struct RealDimension {
  const char* name;
  double FieldModel::*member;
};
inline constexpr RealDimension kRealDimensions[] = {
    {"ball_radius", &FieldModel::ball_radius},
    {"max_robot_radius", &FieldModel::max_robot_radius},
};

// Division A is 12000 mm long, B 9000: a field takes its missing optional
// dimensions from the preset nearer its length.
inline FieldModel presetFor(int field_length) {
  return field_length >= 10500 ? FieldModel::divisionA() : FieldModel::divisionB();
}

// Whether f's lines and arcs are exactly those its dimensions generate.
bool sameMarkings(const FieldModel& f);

// Shortest text that reads back as the same double (human-friendly YAML).
std::string shortest(double v);

}  // namespace geometry_io_detail
}  // namespace dv
