#pragma once
// Distinct point types for the three coordinate spaces dotvision works in, so
// that a camera pixel can never be passed where a field position is expected.
// Units: field millimetres, image pixels, grid pixels; angles in radians.

namespace dv {

// A position in the full camera image. (0, 0) is the center of the top-left
// pixel; u grows to the right (column), v downwards (row).
struct ImagePx {
  double u = 0;
  double v = 0;
};

// A position in a rectified field grid (one cell = the grid's scale in mm).
struct GridPx {
  double x = 0;
  double y = 0;
};

// A position on a horizontal field plane in millimetres (SSL field frame).
struct FieldMm {
  double x = 0;
  double y = 0;
};

// A point in the SSL field frame in millimetres; z = 0 is the carpet.
struct FieldPoint {
  double x = 0;
  double y = 0;
  double z = 0;
  FieldMm xy() const { return {x, y}; }
};

constexpr double kPi = 3.14159265358979323846;

}  // namespace dv
