#pragma once
// The painted field lines as geometric elements (segments and arcs on z = 0)
// with the distance queries calibration needs.
#include <cmath>
#include <string>
#include <vector>

#include "core/units.h"
#include "geometry/field_model.h"

namespace dv {

struct FieldLineElement {
  bool is_arc = false;
  FieldMm a, b;            // segment ends
  FieldMm center;          // arc
  double radius = 0;       // arc, to the line center
  double a1 = 0, a2 = 0;   // arc angles
  double half_thickness = 5;
  std::string name;        // the field file's name of the line or arc

  // Distance from p to the element's center line (clamped to its extent).
  double distance(FieldMm p) const;
  // Signed distance to the infinite line (segment) or the full circle (arc),
  // differentiable for Ceres; valid near the element.
  template <typename T>
  T signedDistance(const T* xy) const {
    if (is_arc) {
      const T dx = xy[0] - T(center.x), dy = xy[1] - T(center.y);
      return sqrt(dx * dx + dy * dy + T(1e-12)) - T(radius);
    }
    const double len = std::hypot(b.x - a.x, b.y - a.y);
    const double nx = -(b.y - a.y) / len, ny = (b.x - a.x) / len;
    return (xy[0] - T(a.x)) * T(nx) + (xy[1] - T(a.y)) * T(ny);
  }
};

class FieldLineModel {
 public:
  explicit FieldLineModel(const FieldModel& field);

  struct Match {
    int element = -1;
    double distance = 1e300;
  };
  Match nearest(FieldMm p) const;
  const std::vector<FieldLineElement>& elements() const { return elements_; }
  // Points along every element, about `step_mm` apart.
  std::vector<FieldMm> samples(double step_mm) const;

 private:
  std::vector<FieldLineElement> elements_;
};

}  // namespace dv
