#include "geometry/calibration/field_line_model.h"

#include <algorithm>

namespace dv {

namespace {
double wrapAngle(double a) {
  a = std::fmod(a, 2 * kPi);
  return a < 0 ? a + 2 * kPi : a;
}
}  // namespace

double FieldLineElement::distance(FieldMm p) const {
  if (is_arc) {
    const double dx = p.x - center.x, dy = p.y - center.y;
    const double span = a2 - a1;
    if (span >= 2 * kPi - 1e-9 || wrapAngle(std::atan2(dy, dx) - a1) <= span)
      return std::abs(std::hypot(dx, dy) - radius);
    const FieldMm e1{center.x + radius * std::cos(a1), center.y + radius * std::sin(a1)};
    const FieldMm e2{center.x + radius * std::cos(a2), center.y + radius * std::sin(a2)};
    return std::min(std::hypot(p.x - e1.x, p.y - e1.y), std::hypot(p.x - e2.x, p.y - e2.y));
  }
  const double dx = b.x - a.x, dy = b.y - a.y;
  const double l2 = dx * dx + dy * dy;
  double t = l2 > 0 ? ((p.x - a.x) * dx + (p.y - a.y) * dy) / l2 : 0;
  t = std::clamp(t, 0.0, 1.0);
  return std::hypot(p.x - (a.x + t * dx), p.y - (a.y + t * dy));
}

FieldLineModel::FieldLineModel(const FieldModel& field) {
  for (const auto& l : field.lines) {
    FieldLineElement e;
    e.a = l.p1, e.b = l.p2, e.half_thickness = l.thickness / 2, e.name = l.name;
    if (std::hypot(e.b.x - e.a.x, e.b.y - e.a.y) > 1e-6) elements_.push_back(e);
  }
  for (const auto& arc : field.arcs) {
    FieldLineElement e;
    e.is_arc = true;
    e.center = arc.center, e.radius = arc.radius, e.a1 = arc.a1, e.a2 = arc.a2;
    e.half_thickness = arc.thickness / 2;
    e.name = arc.name;
    if (arc.radius > 0) elements_.push_back(e);
  }
}

FieldLineModel::Match FieldLineModel::nearest(FieldMm p) const {
  Match m;
  for (size_t i = 0; i < elements_.size(); ++i) {
    const double d = elements_[i].distance(p);
    if (d < m.distance) m = {int(i), d};
  }
  return m;
}

std::vector<FieldMm> FieldLineModel::samples(double step_mm) const {
  std::vector<FieldMm> out;
  for (const auto& e : elements_) {
    if (e.is_arc) {
      const double len = e.radius * (e.a2 - e.a1);
      const int n = std::max(2, int(std::ceil(len / step_mm)));
      for (int i = 0; i < n; ++i) {
        const double t = e.a1 + (e.a2 - e.a1) * (i + 0.5) / n;
        out.push_back({e.center.x + e.radius * std::cos(t), e.center.y + e.radius * std::sin(t)});
      }
    } else {
      const double len = std::hypot(e.b.x - e.a.x, e.b.y - e.a.y);
      const int n = std::max(1, int(std::ceil(len / step_mm)));
      for (int i = 0; i <= n; ++i) {
        const double t = double(i) / n;
        out.push_back({e.a.x + t * (e.b.x - e.a.x), e.a.y + t * (e.b.y - e.a.y)});
      }
    }
  }
  return out;
}

}  // namespace dv
