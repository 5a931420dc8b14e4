#include "synth/renderer.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <opencv2/core/utility.hpp>
#include <opencv2/imgcodecs.hpp>
#include <stdexcept>

#include "synth/carpet_texture.h"
#include "synth/random.h"
#include "synth/sensor_model.h"
#include "synth/tile_bins.h"

namespace dv {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kRobotRadius = RobotPatternGeometry::kMaxRadius;  // 90 mm body
// The flat front of the body. The rules' pattern area (R85 cut at 55 mm) must
// fit on the top; a few mm of black top beyond it, as on real robots.
constexpr double kRobotFrontCut = 60;
constexpr double kWallHeight = 100, kWallThickness = 50;
constexpr double kFarDistance = 60000;  // mm; floor beyond this is "hall"
constexpr double kLinePieceLength = 150;  // mm, line pieces binned per tile

struct V3 {
  double x, y, z;
};
inline V3 operator-(V3 a, V3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline V3 operator+(V3 a, V3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
inline V3 operator*(double s, V3 a) { return {s * a.x, s * a.y, s * a.z}; }
inline double dot(V3 a, V3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline V3 normalized(V3 a) { return (1.0 / std::sqrt(dot(a, a))) * a; }

inline Rgb scale(const Rgb& c, double s) { return {c.r * s, c.g * s, c.b * s}; }

// Key light direction (towards the light), slightly off vertical, and the
// Lambert-plus-ambient factor normalised so horizontal surfaces get exactly 1:
// the scene's colors are what the top of a robot or the carpet shows.
const V3 kLight = normalized({0.3, -0.2, 1.0});
constexpr double kAmbient = 0.4;
inline double shade(V3 n) {
  return (kAmbient + (1 - kAmbient) * std::max(0.0, dot(n, kLight))) /
         (kAmbient + (1 - kAmbient) * kLight.z);
}

inline double smoothstep(double e0, double e1, double x) {
  const double t = std::clamp((x - e0) / (e1 - e0), 0.0, 1.0);
  return t * t * (3 - 2 * t);
}

// A piece of a painted line: a rectangle along a segment, or a ring sector.
struct LinePiece {
  bool arc = false;
  double ax = 0, ay = 0, dx = 1, dy = 0;  // segment start and unit direction
  double s0 = 0, s1 = 0;                  // extent along the direction
  double cx = 0, cy = 0, r = 0;           // arc center and radius
  double a0 = 0, a1 = 0;                  // arc angle range
  double half = 5;                        // half the thickness
  bool contains(double x, double y) const {
    if (!arc) {
      const double px = x - ax, py = y - ay;
      const double s = px * dx + py * dy, n = -px * dy + py * dx;
      return s >= s0 && s <= s1 && std::abs(n) <= half;
    }
    const double ex = x - cx, ey = y - cy;
    const double d = std::sqrt(ex * ex + ey * ey);
    if (std::abs(d - r) > half) return false;
    double a = std::atan2(ey, ex);
    if (a < a0) a += 2 * kPi;
    return a >= a0 && a <= a1;
  }
};

struct Box {
  V3 lo, hi;
  Rgb color;
};

// One robot at one instant, with its colors resolved.
struct RobotPose {
  double x = 0, y = 0, c = 1, s = 0, h = 140;
  Rgb center;
  Rgb side[4];
  bool moving = false;
};

struct BallPose {
  V3 c{0, 0, 0};
  bool moving = false;
};

struct CameraRays {
  double f = 1, cx = 0, cy = 0, k = 0;
  double m[9];  // camera -> field rotation, row-major
  V3 origin{0, 0, 0};
  int width = 0, height = 0;
  // Unit direction of the ray through image point (u, v); false where the
  // distortion model has no ray (k < 0 beyond its fold).
  std::optional<CameraModel> lens;  // a lens with terms beyond the league's
  bool ray(double u, double v, V3& d) const {
    double nx, ny;
    if (lens) {
      if (!(lens->undistortPixel({u, v}, &nx, &ny) > 0)) return false;
    } else {
      const double dx = (u - cx) / f, dy = (v - cy) / f;
      const double s = 1 + k * (dx * dx + dy * dy);
      if (!(s > 0)) return false;
      nx = dx * s, ny = dy * s;
    }
    d = normalized({m[0] * nx + m[1] * ny + m[2], m[3] * nx + m[4] * ny + m[5],
                    m[6] * nx + m[7] * ny + m[8]});
    return true;
  }
};

CameraRays makeRays(const CameraCalibration& c) {
  CameraRays r;
  r.f = c.focal_length, r.cx = c.principal_point_x, r.cy = c.principal_point_y;
  r.k = c.distortion;
  if (c.lens.any()) r.lens.emplace(c);
  // Same rotation as CameraModel::pixelRay: R(q^-1) after SSL-Vision's
  // normalisation rule, so rays are the exact inverse of fieldToImage.
  double x = c.q0, y = c.q1, z = c.q2, w = c.q3;
  const double n2 = x * x + y * y + z * z + w * w;
  if (std::abs(1.0 - n2) > 1e-6 && n2 > 0) {
    const double n = std::sqrt(n2);
    x /= n, y /= n, z /= n, w /= n;
  }
  const double m2 = x * x + y * y + z * z + w * w;
  const Eigen::Matrix3d inv = quaternionMatrix(-x / m2, -y / m2, -z / m2, w / m2);
  for (int i = 0; i < 9; ++i) r.m[i] = inv(i / 3, i % 3);
  const Eigen::Vector3d p = CameraModel(c).position();
  r.origin = {p.x(), p.y(), p.z()};
  r.width = int(c.image_width), r.height = int(c.image_height);
  return r;
}

// Pixel box of a set of field points; the whole image when any of them does
// not project (behind the camera, beyond the distortion fold).
PixelBox projectBox(const CameraModel& cam, const std::vector<FieldPoint>& pts, int width,
                    int height, double margin) {
  double u0 = kInf, v0 = kInf, u1 = -kInf, v1 = -kInf;
  for (const FieldPoint& p : pts) {
    const auto px = cam.fieldToImage(p);
    if (!px) return {0, 0, width - 1, height - 1};
    u0 = std::min(u0, px->u), u1 = std::max(u1, px->u);
    v0 = std::min(v0, px->v), v1 = std::max(v1, px->v);
  }
  if (u1 < -margin || v1 < -margin || u0 > width - 1 + margin || v0 > height - 1 + margin)
    return {};
  auto clampI = [](double x, int hi) { return int(std::clamp(x, -1.0, double(hi) + 1)); };
  return {clampI(std::floor(u0 - margin), width - 1), clampI(std::floor(v0 - margin), height - 1),
          clampI(std::ceil(u1 + margin), width - 1), clampI(std::ceil(v1 + margin), height - 1)};
}

// Points on the edges of an axis-aligned box, dense enough that distortion
// cannot bend an edge outside their bounding box by more than the margin.
std::vector<FieldPoint> boxEdgePoints(V3 lo, V3 hi, int steps) {
  std::vector<FieldPoint> pts;
  const double xs[2] = {lo.x, hi.x}, ys[2] = {lo.y, hi.y}, zs[2] = {lo.z, hi.z};
  for (int i = 0; i <= steps; ++i) {
    const double a = double(i) / steps;
    for (int p = 0; p < 2; ++p)
      for (int q = 0; q < 2; ++q) {
        pts.push_back({lo.x + a * (hi.x - lo.x), ys[p], zs[q]});
        pts.push_back({xs[p], lo.y + a * (hi.y - lo.y), zs[q]});
        pts.push_back({xs[p], ys[q], lo.z + a * (hi.z - lo.z)});
      }
  }
  return pts;
}

std::vector<FieldPoint> circlePoints(double x, double y, double z, double r, int n) {
  std::vector<FieldPoint> pts;
  for (int i = 0; i < n; ++i) {
    const double a = 2 * kPi * i / n;
    // Circumscribed polygon: vertices at r / cos(pi/n) enclose the circle.
    const double rr = r / std::cos(kPi / n);
    pts.push_back({x + rr * std::cos(a), y + rr * std::sin(a), z});
  }
  return pts;
}

Rgb markerColor(const SceneMaterials& m, MarkerColor c) {
  return c == MarkerColor::Green ? m.green : m.pink;
}

}  // namespace

struct Renderer::Impl {
  const SceneSpec& spec;
  FieldRect carpet;
  CarpetTexture texture;
  std::vector<LinePiece> lines;
  std::vector<Box> boxes;
  std::vector<CameraRays> rays;
  std::vector<CameraModel> models;
  std::vector<TileBins> line_bins, box_bins;  // static, per camera
  std::vector<cv::Mat> uneven;                // per camera, empty when even

  explicit Impl(const SceneSpec& s) : spec(s) {
    carpet = s.field.withBoundary();
    FieldRect tex_area{carpet.x_min - 200, carpet.x_max + 200, carpet.y_min - 200,
                       carpet.y_max + 200};
    texture = CarpetTexture(tex_area, 4.0, s.seed);
    buildLines();
    buildBoxes();
    for (const SceneCamera& c : s.cameras) {
      rays.push_back(makeRays(c.calib));
      models.emplace_back(c.calib);
    }
    for (size_t i = 0; i < s.cameras.size(); ++i) binStatic(i);
  }

  void buildLines() {
    for (const FieldLine& l : spec.field.lines) {
      const double lx = l.p2.x - l.p1.x, ly = l.p2.y - l.p1.y;
      const double len = std::hypot(lx, ly);
      if (!(len > 0)) continue;
      LinePiece base;
      base.dx = lx / len, base.dy = ly / len;
      base.half = l.thickness / 2;
      // Square ends reaching half a thickness past the end points, so that
      // lines meeting at a corner close it.
      base.ax = l.p1.x - base.dx * base.half, base.ay = l.p1.y - base.dy * base.half;
      const double total = len + l.thickness;
      const int n = std::max(1, int(std::ceil(total / kLinePieceLength)));
      for (int i = 0; i < n; ++i) {
        LinePiece p = base;
        p.s0 = total * i / n, p.s1 = total * (i + 1) / n;
        lines.push_back(p);
      }
    }
    for (const FieldArc& a : spec.field.arcs) {
      double a0 = std::remainder(a.a1, 2 * kPi);
      const double span = a.span();
      const int n = std::max(1, int(std::ceil(span * a.radius / kLinePieceLength)));
      for (int i = 0; i < n; ++i) {
        LinePiece p;
        p.arc = true;
        p.cx = a.center.x, p.cy = a.center.y, p.r = a.radius, p.half = a.thickness / 2;
        p.a0 = a0 + span * i / n, p.a1 = a0 + span * (i + 1) / n;
        if (p.a0 > kPi) p.a0 -= 2 * kPi, p.a1 -= 2 * kPi;
        lines.push_back(p);
      }
    }
  }

  void buildBoxes() {
    const SceneMaterials& m = spec.materials;
    const FieldRect& r = carpet;
    const double t = kWallThickness, h = kWallHeight;
    boxes.push_back({{r.x_min - t, r.y_min - t, 0}, {r.x_max + t, r.y_min, h}, m.wall});
    boxes.push_back({{r.x_min - t, r.y_max, 0}, {r.x_max + t, r.y_max + t, h}, m.wall});
    boxes.push_back({{r.x_min - t, r.y_min, 0}, {r.x_min, r.y_max, h}, m.wall});
    boxes.push_back({{r.x_max, r.y_min, 0}, {r.x_max + t, r.y_max, h}, m.wall});
    const FieldModel& f = spec.field;
    const double gw = f.goal_width / 2.0, gh = f.goal_height, g = FieldModel::kGoalWallThickness;
    // goal_depth runs from the outer edge of the goal line to the inner back wall.
    const double front = f.field_length / 2.0 + f.line_thickness / 2.0;
    const double back = front + f.goal_depth;
    for (double sx : {-1.0, 1.0}) {
      auto add = [&](double xa, double xb, double y0, double y1) {
        boxes.push_back({{std::min(sx * xa, sx * xb), y0, 0},
                         {std::max(sx * xa, sx * xb), y1, gh}, m.goal});
      };
      add(back, back + g, -gw - g, gw + g);
      add(front, back, gw, gw + g);
      add(front, back, -gw - g, -gw);
    }
    for (const SceneBox& c : spec.clutter)
      boxes.push_back({{c.min.x, c.min.y, c.min.z}, {c.max.x, c.max.y, c.max.z}, c.color});
  }

  void binStatic(size_t ci) {
    const CameraRays& cr = rays[ci];
    const CameraModel& cam = models[ci];
    TileBins lb, bb;
    lb.reset(cr.width, cr.height);
    bb.reset(cr.width, cr.height);
    for (size_t i = 0; i < lines.size(); ++i) {
      const LinePiece& p = lines[i];
      std::vector<FieldPoint> pts;
      if (!p.arc) {
        for (double s : {p.s0, p.s1})
          for (double n : {-p.half, p.half})
            pts.push_back({p.ax + p.dx * s - p.dy * n, p.ay + p.dy * s + p.dx * n, 0});
      } else {
        for (int k = 0; k <= 4; ++k) {
          const double a = p.a0 + (p.a1 - p.a0) * k / 4;
          for (double rr : {p.r - p.half, (p.r + p.half) / std::cos((p.a1 - p.a0) / 8)})
            pts.push_back({p.cx + rr * std::cos(a), p.cy + rr * std::sin(a), 0});
        }
      }
      lb.add(uint32_t(i), projectBox(cam, pts, cr.width, cr.height, 2));
    }
    for (size_t i = 0; i < boxes.size(); ++i)
      bb.add(uint32_t(i), projectBox(cam, boxEdgePoints(boxes[i].lo, boxes[i].hi, 24), cr.width,
                                     cr.height, 2));
    lb.finish();
    bb.finish();
    line_bins.push_back(std::move(lb));
    box_bins.push_back(std::move(bb));
    const SceneLighting& l = spec.lighting;
    cv::Mat light;
    if (l.uneven_ratio != 1 || l.vignetting != 0)
      light = unevenLightMap(cr.width, cr.height, l.uneven_ratio, l.uneven_direction);
    if (l.vignetting != 0) applyVignetting(light, l.vignetting);
    uneven.push_back(light);
  }

  // Field-space light: sun patches and cast shadows of the hall.
  double fieldLight(double x, double y) const {
    double light = 1;
    auto patch = [&](const LightPatch& p) {
      const double ex = x - p.center.x, ey = y - p.center.y;
      const double c = std::cos(p.angle), s = std::sin(p.angle);
      const double a = (ex * c + ey * s) / p.radius_x, b = (-ex * s + ey * c) / p.radius_y;
      const double rho = std::sqrt(a * a + b * b);
      const double w = 1 - smoothstep(1 - p.softness / 2, 1 + p.softness / 2, rho);
      light *= 1 + (p.gain - 1) * w;
    };
    for (const LightPatch& p : spec.lighting.sun_patches) patch(p);
    for (const LightPatch& p : spec.lighting.shadows) patch(p);
    return light;
  }

  // Objects of one render: poses per time sample and their tile bins.
  struct Instant {
    int samples = 1;                        // time samples
    std::vector<std::vector<RobotPose>> robots;  // [time][robot]
    std::vector<BallPose> ball;             // [time]
    bool ball_present = false;
    TileBins bins;  // ids: robots 0..n-1, ball n
  };

  void poses(Instant& in, double t_mid, size_t ci, bool blur) const {
    const SceneMaterials& m = spec.materials;
    const double tau = spec.lighting.exposure_time;
    in.samples = blur ? std::max(1, spec.motion_blur_samples) : 1;
    in.robots.assign(in.samples, {});
    in.ball.assign(in.samples, {});
    in.ball_present = spec.ball.present;
    const bool ball_moves = ballMoves(spec.ball);
    for (int k = 0; k < in.samples; ++k) {
      const double t = in.samples == 1 ? t_mid : t_mid + tau * ((k + 0.5) / in.samples - 0.5);
      for (const SceneRobot& r : spec.robots) {
        RobotPose p;
        const FieldMm xy = robotPositionAt(r, t);
        const double th = robotOrientationAt(r, t);
        p.x = xy.x, p.y = xy.y, p.c = std::cos(th), p.s = std::sin(th), p.h = r.height;
        p.center = r.team == Team::Yellow ? m.yellow : m.blue;
        const auto colors = patternColors(r.id);
        for (int i = 0; i < 4; ++i) p.side[i] = markerColor(m, colors[i]);
        p.moving = r.velocity.x != 0 || r.velocity.y != 0 || r.angular_velocity != 0;
        in.robots[k].push_back(p);
      }
      const FieldPoint b = ballPositionAt(spec.ball, spec.field, t);
      in.ball[k] = {{b.x, b.y, b.z}, ball_moves};
    }
    const CameraRays& cr = rays[ci];
    const CameraModel& cam = models[ci];
    in.bins.reset(cr.width, cr.height);
    const size_t n = spec.robots.size();
    for (size_t i = 0; i < n; ++i) {
      PixelBox box;
      for (int k = 0; k < in.samples; ++k) {
        const RobotPose& p = in.robots[k][i];
        // Body top and the contact shadow on the carpet around it.
        std::vector<FieldPoint> pts = circlePoints(p.x, p.y, p.h, kRobotRadius, 16);
        auto base = circlePoints(p.x, p.y, 0, kRobotRadius + kShadowReach, 16);
        pts.insert(pts.end(), base.begin(), base.end());
        box.add(projectBox(cam, pts, cr.width, cr.height, 3));
      }
      in.bins.add(uint32_t(i), box);
    }
    if (in.ball_present) {
      const double r = spec.field.ball_radius;
      PixelBox box;
      for (int k = 0; k < in.samples; ++k) {
        const V3 c = in.ball[k].c;
        std::vector<FieldPoint> pts =
            boxEdgePoints({c.x - r, c.y - r, c.z - r}, {c.x + r, c.y + r, c.z + r}, 2);
        auto shadow = circlePoints(c.x, c.y, 0, kBallShadowReach * r, 12);
        pts.insert(pts.end(), shadow.begin(), shadow.end());
        box.add(projectBox(cam, pts, cr.width, cr.height, 3));
      }
      in.bins.add(uint32_t(n), box);
    }
    in.bins.finish();
  }

  static constexpr double kShadowReach = 60;      // mm beyond the robot body
  static constexpr double kBallShadowReach = 1.8;  // ball radii

  // Nearest hit of a ray with a robot body (vertical prism: circle of radius
  // 90 cut flat at the front). Returns the distance and writes the color
  // (before light) and whether it hit the top.
  double hitRobot(const RobotPose& p, V3 o, V3 d, Rgb& color) const {
    // Ray in the robot frame (x forward, y left).
    const double ox = o.x - p.x, oy = o.y - p.y;
    const double lox = p.c * ox + p.s * oy, loy = -p.s * ox + p.c * oy;
    const double ldx = p.c * d.x + p.s * d.y, ldy = -p.s * d.x + p.c * d.y;
    double best = kInf;
    const SceneMaterials& m = spec.materials;
    constexpr double R = kRobotRadius, R2 = R * R;
    // Top plane.
    if (d.z != 0) {
      const double t = (p.h - o.z) / d.z;
      if (t > 0) {
        const double x = lox + t * ldx, y = loy + t * ldy;
        if (x <= kRobotFrontCut && x * x + y * y <= R2) {
          best = t;
          color = m.robot_top;
          constexpr double rc = RobotPatternGeometry::kCenterBlobRadius;
          constexpr double rs = RobotPatternGeometry::kSideBlobRadius;
          if (x * x + y * y <= rc * rc) {
            color = p.center;
          } else {
            for (int i = 0; i < 4; ++i) {
              const double ex = x - RobotPatternGeometry::kSideBlobs[i].x;
              const double ey = y - RobotPatternGeometry::kSideBlobs[i].y;
              if (ex * ex + ey * ey <= rs * rs) {
                color = p.side[i];
                break;
              }
            }
          }
        }
      }
    }
    // Round side.
    const double a = ldx * ldx + ldy * ldy;
    if (a > 1e-18) {
      const double b = lox * ldx + loy * ldy, c = lox * lox + loy * loy - R2;
      const double disc = b * b - a * c;
      if (disc >= 0) {
        const double t = (-b - std::sqrt(disc)) / a;  // entering the cylinder
        if (t > 0 && t < best) {
          const double z = o.z + t * d.z, x = lox + t * ldx, y = loy + t * ldy;
          if (z >= 0 && z <= p.h && x <= kRobotFrontCut) {
            best = t;
            // Normal back in the field frame.
            const V3 n{(p.c * x - p.s * y) / R, (p.s * x + p.c * y) / R, 0};
            color = scale(m.robot_body, shade(n));
          }
        }
      }
    }
    // Flat front.
    if (ldx < 0) {
      const double t = (kRobotFrontCut - lox) / ldx;
      if (t > 0 && t < best) {
        const double z = o.z + t * d.z, y = loy + t * ldy;
        if (z >= 0 && z <= p.h && y * y <= R2 - kRobotFrontCut * kRobotFrontCut) {
          best = t;
          color = scale(m.robot_body, shade({p.c, p.s, 0}));
        }
      }
    }
    return best;
  }

  double hitBall(V3 center, V3 o, V3 d, Rgb& color) const {
    const double r = spec.field.ball_radius;
    const V3 oc = o - center;
    const double b = dot(oc, d), c = dot(oc, oc) - r * r;
    const double disc = b * b - c;
    if (disc < 0) return kInf;
    const double t = -b - std::sqrt(disc);
    if (!(t > 0)) return kInf;
    const V3 n = (1.0 / r) * (oc + t * d);
    const V3 h = normalized(kLight - d);
    const double spec_term = std::pow(std::max(0.0, dot(n, h)), 30) * 70;
    const Rgb& m = spec.materials.ball;
    const double s = shade(n);
    color = {m.r * s + spec_term, m.g * s + spec_term, m.b * s + spec_term};
    return t;
  }

  static double hitBox(const Box& bx, V3 o, V3 inv, V3& normal) {
    double t0 = -kInf, t1 = kInf;
    int axis = -1;
    double sign = 0;
    const double lo[3] = {bx.lo.x, bx.lo.y, bx.lo.z}, hi[3] = {bx.hi.x, bx.hi.y, bx.hi.z};
    const double oo[3] = {o.x, o.y, o.z}, ii[3] = {inv.x, inv.y, inv.z};
    for (int i = 0; i < 3; ++i) {
      double ta = (lo[i] - oo[i]) * ii[i], tb = (hi[i] - oo[i]) * ii[i];
      double sg = -1;  // entering through the low face: normal -axis
      if (ta > tb) std::swap(ta, tb), sg = 1;
      if (std::isnan(ta)) continue;  // ray parallel and on the face plane
      if (ta > t0) t0 = ta, axis = i, sign = sg;
      t1 = std::min(t1, tb);
    }
    if (!(t0 <= t1) || !(t0 > 0) || axis < 0) return kInf;
    normal = {axis == 0 ? sign : 0, axis == 1 ? sign : 0, axis == 2 ? sign : 0};
    return t0;
  }

  // Radiance along one ray at time sample k.
  Rgb trace(size_t ci, int tile, V3 d, const Instant& in, int k) const {
    const V3 o = rays[ci].origin;
    double best = kInf;
    Rgb color{0, 0, 0};
    bool ground = false;
    // Carpet / floor.
    if (d.z < 0) {
      best = -o.z / d.z;
      ground = true;
    }
    // Walls and goals.
    const TileBins& bb = box_bins[ci];
    if (!bb.emptyTile(tile)) {
      const V3 inv{1 / d.x, 1 / d.y, 1 / d.z};
      for (const uint32_t* it = bb.begin(tile); it != bb.end(tile); ++it) {
        V3 n{0, 0, 1};
        const double t = hitBox(boxes[*it], o, inv, n);
        if (t < best) best = t, ground = false, color = scale(boxes[*it].color, shade(n));
      }
    }
    // Robots and the ball.
    const size_t nr = spec.robots.size();
    const uint32_t* dyn_begin = in.bins.begin(tile);
    const uint32_t* dyn_end = in.bins.end(tile);
    for (const uint32_t* it = dyn_begin; it != dyn_end; ++it) {
      Rgb c;
      const double t = *it < nr ? hitRobot(in.robots[k][*it], o, d, c) : hitBall(in.ball[k].c, o, d, c);
      if (t < best) best = t, ground = false, color = c;
    }
    if (best == kInf) return spec.materials.background;
    const V3 p = o + best * d;
    if (!ground) return scale(color, fieldLight(p.x, p.y));
    if (!carpet.contains({p.x, p.y})) {
      if (best > kFarDistance) return spec.materials.background;
      return scale(spec.materials.floor, fieldLight(p.x, p.y));
    }
    // Carpet with texture, painted lines, light and contact shadows.
    const double tex = texture.at(p.x, p.y);
    color = scale(spec.materials.carpet, std::max(0.0, 1 + spec.materials.carpet_texture * tex));
    const TileBins& lb = line_bins[ci];
    for (const uint32_t* it = lb.begin(tile); it != lb.end(tile); ++it)
      if (lines[*it].contains(p.x, p.y)) {
        color = scale(spec.materials.line,
                      std::max(0.0, 1 + 0.3 * spec.materials.carpet_texture * tex));
        break;
      }
    double light = fieldLight(p.x, p.y);
    const double shadow = spec.lighting.object_shadow;
    if (shadow > 0) {
      for (const uint32_t* it = dyn_begin; it != dyn_end; ++it) {
        if (*it < nr) {
          const RobotPose& r = in.robots[k][*it];
          const double dist = std::hypot(p.x - r.x, p.y - r.y);
          light *= 1 - shadow * (1 - smoothstep(kRobotRadius - 10, kRobotRadius + kShadowReach, dist));
        } else {
          const V3 c = in.ball[k].c;
          const double rb = spec.field.ball_radius;
          const double dist = std::hypot(p.x - c.x, p.y - c.y);
          // Fades as the ball leaves the floor.
          const double lift = std::clamp(1 - (c.z - rb) / (4 * rb), 0.0, 1.0);
          light *= 1 - shadow * lift * (1 - smoothstep(0.2 * rb, kBallShadowReach * rb, dist));
        }
      }
    }
    return scale(color, light);
  }

  // Radiance image (CV_32FC3, B G R) of camera ci around time t_mid.
  void radiance(size_t ci, double t_mid, bool blur, cv::Mat& out) const {
    Instant in;
    poses(in, t_mid, ci, blur);
    const CameraRays& cr = rays[ci];
    out.create(cr.height, cr.width, CV_32FC3);
    const int aa = std::max(1, spec.antialias);
    const double inv_aa = 1.0 / aa;
    cv::parallel_for_(cv::Range(0, cr.height), [&](const cv::Range& range) {
      for (int v = range.start; v < range.end; ++v) {
        float* row = out.ptr<float>(v);
        for (int u = 0; u < cr.width; ++u) {
          const int tile = line_bins[ci].tileIndex(u, v);
          // Time samples only where something moving may be on the pixel.
          int times = 1;
          if (in.samples > 1)
            for (const uint32_t* it = in.bins.begin(tile); it != in.bins.end(tile); ++it) {
              const bool moving = *it < spec.robots.size() ? in.robots[0][*it].moving
                                                           : in.ball[0].moving;
              if (moving) {
                times = in.samples;
                break;
              }
            }
          double r = 0, g = 0, b = 0;
          int n = 0;
          for (int sy = 0; sy < aa; ++sy)
            for (int sx = 0; sx < aa; ++sx) {
              // Stratified samples around the pixel center (integer coords).
              const double su = u + (sx + 0.5) * inv_aa - 0.5, sv = v + (sy + 0.5) * inv_aa - 0.5;
              V3 d;
              if (!cr.ray(su, sv, d)) {
                n += times;
                continue;
              }
              for (int k = 0; k < times; ++k) {
                const Rgb c = trace(ci, tile, d, in, times == 1 ? in.samples / 2 : k);
                r += c.r, g += c.g, b += c.b;
                ++n;
              }
            }
          const double w = 1.0 / n;
          row[3 * u + 0] = float(b * w);
          row[3 * u + 1] = float(g * w);
          row[3 * u + 2] = float(r * w);
        }
      }
    });
  }
};

Renderer::Renderer(const SceneSpec& spec) : spec_(spec) {
  if (spec_.cameras.empty()) throw std::invalid_argument("scene '" + spec_.name + "' has no camera");
  for (const SceneCamera& c : spec_.cameras)
    if (c.calib.image_width == 0 || c.calib.image_height == 0)
      throw std::invalid_argument("camera " + std::to_string(c.calib.camera_id) +
                                  " has no image size");
  if (spec_.antialias < 1) throw std::invalid_argument("antialias must be at least 1");
  if (!(spec_.fps > 0)) throw std::invalid_argument("fps must be positive");
  if (spec_.jpeg_quality < 0 || spec_.jpeg_quality > 100)
    throw std::invalid_argument("jpeg_quality must be 0 (off) to 100");
  if (spec_.jpeg_quality > 0 && spec_.bayer)
    throw std::invalid_argument("jpeg_quality needs RGB frames (bayer false)");
  impl_ = std::make_unique<Impl>(spec_);
}

Renderer::~Renderer() = default;

Geometry Renderer::geometry() const {
  Geometry g;
  g.field = spec_.field;
  for (const SceneCamera& c : spec_.cameras) g.cameras.push_back(c.calib);
  return g;
}

dv::ssl::SSL_DetectionFrame Renderer::truth(int frame, size_t camera_index) const {
  const CameraModel& cam = impl_->models.at(camera_index);
  const CameraCalibration& calib = spec_.cameras[camera_index].calib;
  const double t = frame / spec_.fps;
  dv::ssl::SSL_DetectionFrame f;
  f.set_frame_number(uint32_t(frame));
  f.set_t_capture(t);
  f.set_t_sent(t);
  f.set_camera_id(calib.camera_id);
  auto inside = [&](const std::optional<ImagePx>& px) {
    return px && px->u >= -0.5 && px->v >= -0.5 && px->u < calib.image_width - 0.5 &&
           px->v < calib.image_height - 0.5;
  };
  for (const SceneRobot& r : spec_.robots) {
    const FieldMm xy = robotPositionAt(r, t);
    const auto px = cam.fieldToImage({xy.x, xy.y, r.height});
    if (!inside(px)) continue;
    auto* d = r.team == Team::Yellow ? f.add_robots_yellow() : f.add_robots_blue();
    d->set_confidence(1);
    d->set_robot_id(uint32_t(r.id));
    d->set_x(float(xy.x));
    d->set_y(float(xy.y));
    d->set_orientation(float(robotOrientationAt(r, t)));
    d->set_pixel_x(float(px->u));
    d->set_pixel_y(float(px->v));
    d->set_height(float(r.height));
  }
  if (spec_.ball.present) {
    const FieldPoint b = ballPositionAt(spec_.ball, spec_.field, t);
    const auto px = cam.fieldToImage(b);
    if (inside(px)) {
      auto* d = f.add_balls();
      d->set_confidence(1);
      d->set_area(0);
      d->set_x(float(b.x));
      d->set_y(float(b.y));
      d->set_z(float(b.z));
      d->set_pixel_x(float(px->u));
      d->set_pixel_y(float(px->v));
    }
  }
  return f;
}

cv::Mat Renderer::renderRadiance(double t, size_t camera_index) const {
  if (camera_index >= spec_.cameras.size()) throw std::out_of_range("no such camera");
  cv::Mat out;
  impl_->radiance(camera_index, t, false, out);
  return out;
}

RenderedFrame Renderer::render(int frame, size_t camera_index) const {
  if (camera_index >= spec_.cameras.size()) throw std::out_of_range("no such camera");
  const double t = frame / spec_.fps;
  cv::Mat radiance;
  impl_->radiance(camera_index, t, spec_.motion_blur, radiance);
  const SceneLighting& l = spec_.lighting;
  SensorSettings s;
  const double g = l.exposure * flickerGain(l, t);
  s.gain[0] = g * l.white_balance.b;
  s.gain[1] = g * l.white_balance.g;
  s.gain[2] = g * l.white_balance.r;
  s.saturation = l.saturation;
  s.gamma = l.gamma;
  s.lens_blur_px = spec_.lens_blur_px;
  s.noise_sigma = spec_.noise_sigma;
  s.shot_noise = spec_.shot_noise;
  s.bayer = spec_.bayer;
  s.layout = spec_.bayer_layout;
  s.noise_seed = mixSeed(spec_.seed, uint64_t(frame) + 1, camera_index + 1);
  RenderedFrame out;
  if (spec_.bayer && spec_.write_png) {
    cv::Mat copy = radiance.clone();
    SensorSettings rgb = s;
    rgb.bayer = false;
    out.rgb = applySensor(copy, impl_->uneven[camera_index], rgb);
  }
  out.image = applySensor(radiance, impl_->uneven[camera_index], s);
  if (!spec_.bayer && spec_.jpeg_quality > 0) {
    cv::imencode(".jpg", out.image, out.jpeg, {cv::IMWRITE_JPEG_QUALITY, spec_.jpeg_quality});
    out.image = cv::imdecode(out.jpeg, cv::IMREAD_COLOR);
  }
  out.truth = truth(frame, camera_index);
  return out;
}

}  // namespace dv
