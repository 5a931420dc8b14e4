#include "geometry/calibration/field_symmetry.h"

#include <Eigen/Geometry>
#include <cmath>
#include <cstdio>

namespace dv {

namespace {

// Two readings whose views are closer than this look at "the same place".
constexpr double kMinSeparationMm = 1000;
// The target must be nearer to one reading by this share of their separation.
constexpr double kMinMarginShare = 0.2;

SymmetryDecision describeBoth(const CameraParams& p, const CameraParams& twin, int w, int h) {
  SymmetryDecision d;
  d.position = {p.position[0], p.position[1], p.position[2]};
  d.alternative_position = {twin.position[0], twin.position[1], twin.position[2]};
  d.view = viewCenter(p, w, h);
  d.alternative_view = viewCenter(twin, w, h);
  return d;
}

}  // namespace

CameraParams halfTurnTwin(const CameraParams& p) {
  CameraParams t = p;
  const Eigen::Vector3d r(p.rotation[0], p.rotation[1], p.rotation[2]);
  const Eigen::Matrix3d rot =
      r.norm() > 0 ? Eigen::AngleAxisd(r.norm(), r.normalized()).toRotationMatrix() : Eigen::Matrix3d::Identity();
  // field -> camera of the twin: turn the field back, then the original.
  const Eigen::Matrix3d turned = rot * Eigen::Vector3d(-1, -1, 1).asDiagonal();
  const Eigen::AngleAxisd aa(turned);
  const Eigen::Vector3d v = aa.angle() * aa.axis();
  for (int i = 0; i < 3; ++i) t.rotation[i] = v[i];
  t.position[0] = -p.position[0];
  t.position[1] = -p.position[1];
  return t;
}

FieldMm viewCenter(const CameraParams& p, int width, int height) {
  double xy[2];
  if (backProjectPixel(p.intrinsics, p.rotation, p.position, (width - 1) / 2.0, (height - 1) / 2.0, 0.0, xy))
    return {xy[0], xy[1]};
  return {p.position[0], p.position[1]};
}

SymmetryChoice chooseNearTarget(const CameraParams& found, FieldMm target, const std::string& basis, int w, int h) {
  const CameraParams twin = halfTurnTwin(found);
  const FieldMm a = viewCenter(found, w, h), b = viewCenter(twin, w, h);
  const double da = std::hypot(a.x - target.x, a.y - target.y), db = std::hypot(b.x - target.x, b.y - target.y);
  const double separation = std::hypot(a.x - b.x, a.y - b.y);
  const bool take_twin = db < da;
  SymmetryChoice c{take_twin ? twin : found, {}};
  c.decision = take_twin ? describeBoth(twin, found, w, h) : describeBoth(found, twin, w, h);
  c.decision.basis = basis;
  char buf[200];
  if (separation < kMinSeparationMm) {
    c.decision.decided = false;
    std::snprintf(buf, sizeof buf, "both readings look at nearly the same place (%.0f mm apart)", separation);
    c.decision.reason = buf;
  } else if (std::abs(da - db) < kMinMarginShare * separation) {
    c.decision.decided = false;
    std::snprintf(buf, sizeof buf, "(%.0f, %.0f) is about as near to both readings (%.0f and %.0f mm)", target.x,
                  target.y, da, db);
    c.decision.reason = buf;
  }
  return c;
}

SymmetryChoice chooseInRegion(const std::vector<CameraParams>& readings, const FieldRect& region,
                              const std::string& basis, int w, int h) {
  const FieldMm center{(region.x_min + region.x_max) / 2, (region.y_min + region.y_max) / 2};
  std::vector<CameraParams> inside;
  for (const auto& r : readings)
    for (const CameraParams& p : {r, halfTurnTwin(r)})
      if (region.contains(viewCenter(p, w, h))) inside.push_back(p);
  if (readings.size() == 1 && inside.size() == 2) return chooseNearTarget(readings[0], center, basis, w, h);
  const CameraParams& chosen = inside.size() == 1 ? inside[0] : readings[0];
  SymmetryChoice c{chosen, describeBoth(chosen, halfTurnTwin(chosen), w, h)};
  c.decision.basis = basis;
  char buf[240];
  if (inside.size() != 1) {
    c.decision.decided = false;
    if (inside.empty())
      std::snprintf(buf, sizeof buf, "no reading looks into x %.0f..%.0f, y %.0f..%.0f", region.x_min, region.x_max,
                    region.y_min, region.y_max);
    else
      std::snprintf(buf, sizeof buf, "%zu readings that fit the lines equally well look into it", inside.size());
    c.decision.reason = buf;
  } else if (readings.size() > 1) {
    std::snprintf(buf, sizeof buf, " (the view looks the same in %zu poses; one looks into the region)",
                  2 * readings.size());
    c.decision.basis += buf;
  }
  return c;
}

SymmetryDecision decidedByPoints(const CameraParams& p, int w, int h) {
  SymmetryDecision d = describeBoth(p, halfTurnTwin(p), w, h);
  d.basis = "the given points";
  d.by_points = true;
  return d;
}

std::string SymmetryDecision::describe() const {
  char buf[600];
  if (decided) {
    char alt[100];
    if (by_points)
      std::snprintf(alt, sizeof alt, "what the same clicks give with the field coordinates' signs flipped");
    else
      std::snprintf(alt, sizeof alt, "if that is right, give --near %.0f,%.0f", alternative_view.x,
                    alternative_view.y);
    std::snprintf(buf, sizeof buf,
                  "field symmetry settled by %s: camera at (%.0f, %.0f, %.0f) looking at (%.0f, %.0f); "
                  "the half-turn alternative is a camera at (%.0f, %.0f, %.0f) looking at (%.0f, %.0f) "
                  "(%s)",
                  basis.c_str(), position.x, position.y, position.z, view.x, view.y, alternative_position.x,
                  alternative_position.y, alternative_position.z, alternative_view.x, alternative_view.y, alt);
  } else {
    std::snprintf(buf, sizeof buf,
                  "field symmetry NOT settled by %s: %s; the camera is at (%.0f, %.0f, %.0f) looking at "
                  "(%.0f, %.0f), or at (%.0f, %.0f, %.0f) looking at (%.0f, %.0f)",
                  basis.c_str(), reason.c_str(), position.x, position.y, position.z, view.x, view.y,
                  alternative_position.x, alternative_position.y, alternative_position.z, alternative_view.x,
                  alternative_view.y);
  }
  return buf;
}

}  // namespace dv
