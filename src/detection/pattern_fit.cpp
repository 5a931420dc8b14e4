#include "detection/pattern_fit.h"

#include <algorithm>
#include <cmath>

#include "geometry/robot_pattern.h"

namespace dv {
namespace {

using G = RobotPatternGeometry;

constexpr double kTopRadius = G::kTopRadius;  // 85
constexpr double kFrontCut = G::kFrontCut;    // 55
constexpr int kArcVertices = 16;

struct Poly {
  std::array<FieldMm, kArcVertices + 1> v;
  int n = kArcVertices + 1;
};

// Convex polygon inside the shrunk robot top: arc vertices from the left end
// of the flat front around the back to its right end; the closing edge is the
// flat front.
Poly topPolygon(const FieldMm& c, double orientation, double tolerance) {
  const double r = kTopRadius - tolerance;
  const double cut = kFrontCut - tolerance;
  const double half = std::acos(std::clamp(cut / r, -1.0, 1.0));
  const double cs = std::cos(orientation), sn = std::sin(orientation);
  Poly p;
  for (int i = 0; i <= kArcVertices; ++i) {
    const double a = half + (2 * kPi - 2 * half) * i / kArcVertices;
    const double x = r * std::cos(a), y = r * std::sin(a);
    p.v[i] = {c.x + cs * x - sn * y, c.y + sn * x + cs * y};
  }
  return p;
}

// True when some edge normal of `a` separates the two polygons.
bool separatedByEdgeOf(const Poly& a, const Poly& b) {
  for (int i = 0; i < a.n; ++i) {
    const FieldMm& p = a.v[i];
    const FieldMm& q = a.v[(i + 1) % a.n];
    const double nx = q.y - p.y, ny = p.x - q.x;  // outward for CCW order
    double amax = -1e300, bmin = 1e300;
    for (int k = 0; k < a.n; ++k) amax = std::max(amax, nx * a.v[k].x + ny * a.v[k].y);
    for (int k = 0; k < b.n; ++k) bmin = std::min(bmin, nx * b.v[k].x + ny * b.v[k].y);
    if (bmin > amax) return true;
  }
  return false;
}

}  // namespace

FieldMm patternOffset(int slot) {
  if (slot <= 0) return {0, 0};
  return G::kSideBlobs[slot - 1];
}

double wrapAngle(double a) {
  a = std::remainder(a, 2 * kPi);
  if (a <= -kPi) a += 2 * kPi;
  return a;
}

FieldMm slotPosition(const FieldMm& position, double orientation, int slot) {
  const FieldMm o = patternOffset(slot);
  const double cs = std::cos(orientation), sn = std::sin(orientation);
  return {position.x + cs * o.x - sn * o.y, position.y + sn * o.x + cs * o.y};
}

PatternPose fitPattern(const FieldMm* points, const int* slots, int n, double score_scale) {
  return fitPattern(points, slots, n, FitTolerance{score_scale});
}

PatternPose fitPattern(const FieldMm* points, const int* slots, int n, const FitTolerance& tolerance) {
  PatternPose pose;
  if (n < 1) return pose;
  double qx = 0, qy = 0, bx = 0, by = 0;
  for (int i = 0; i < n; ++i) {
    const FieldMm o = patternOffset(slots[i]);
    qx += o.x, qy += o.y, bx += points[i].x, by += points[i].y;
  }
  qx /= n, qy /= n, bx /= n, by /= n;
  double s_cos = 0, s_sin = 0;
  for (int i = 0; i < n; ++i) {
    const FieldMm o = patternOffset(slots[i]);
    const double ux = o.x - qx, uy = o.y - qy;
    const double vx = points[i].x - bx, vy = points[i].y - by;
    s_cos += ux * vx + uy * vy;
    s_sin += ux * vy - uy * vx;
  }
  const double a = std::atan2(s_sin, s_cos);
  const double cs = std::cos(a), sn = std::sin(a);
  pose.orientation = wrapAngle(a);
  pose.position = {bx - (cs * qx - sn * qy), by - (sn * qx + cs * qy)};
  double score = 1;
  for (int i = 0; i < n; ++i) {
    const FieldMm o = patternOffset(slots[i]);
    const double ex = points[i].x - (pose.position.x + cs * o.x - sn * o.y);
    const double ey = points[i].y - (pose.position.y + sn * o.x + cs * o.y);
    double e2 = ex * ex + ey * ey;
    if (tolerance.stretch != 1) {
      const double along = (ex * tolerance.along_x + ey * tolerance.along_y) / tolerance.stretch;
      const double across = ey * tolerance.along_x - ex * tolerance.along_y;
      e2 = along * along + across * across;
    }
    e2 /= tolerance.mm * tolerance.mm;
    score = std::min(score, 1 / (1 + e2));
  }
  pose.score = score;
  return pose;
}

bool robotTopsOverlap(const FieldMm& a, double orientation_a, const FieldMm& b,
                      double orientation_b, double tolerance) {
  const double d = std::hypot(a.x - b.x, a.y - b.y);
  if (d >= 2 * (kTopRadius - tolerance)) return false;
  if (d < 2 * (kFrontCut - tolerance)) return true;  // both contain that disc
  const Poly pa = topPolygon(a, orientation_a, tolerance);
  const Poly pb = topPolygon(b, orientation_b, tolerance);
  return !separatedByEdgeOf(pa, pb) && !separatedByEdgeOf(pb, pa);
}

double distanceToRobotTop(const FieldMm& p, const FieldMm& center, double orientation) {
  const double cs = std::cos(orientation), sn = std::sin(orientation);
  const double dx = p.x - center.x, dy = p.y - center.y;
  const double x = cs * dx + sn * dy, y = -sn * dx + cs * dy;  // robot frame
  const double r = std::hypot(x, y);
  if (r <= kTopRadius && x <= kFrontCut) return 0;
  const double chord = std::sqrt(kTopRadius * kTopRadius - kFrontCut * kFrontCut);
  // Nearest point on the flat front (clamped to the chord) ...
  const double cy = std::clamp(y, -chord, chord);
  double best = std::hypot(x - kFrontCut, y - cy);
  // ... or on the arc, where the radial projection lies behind the cut.
  if (r > 0 && kTopRadius * x / r <= kFrontCut) best = std::min(best, r - kTopRadius);
  return std::max(best, 0.0);
}

double minBallOutsideDistance(double ball_radius) { return 0.49186 * ball_radius; }

}  // namespace dv
