#include "synth/scene.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <stdexcept>

#include "synth/random.h"

namespace dv {

namespace {

Eigen::Vector3d vec(const FieldPoint& p) { return {p.x, p.y, p.z}; }

// Robots and the ball must stay this far inside the walls (robot radius plus
// a little air).
constexpr double kWallClearance = 110;
constexpr double kRobotRadius = RobotPatternGeometry::kMaxRadius;  // body

// Inside the walls and clear of both goals' walls (their inner faces: the
// back wall at goal_depth behind the goal line, the side walls at the goal
// posts), so that no robot stands in a wall the renderer draws.
bool insideWalls(const FieldModel& f, FieldMm p, double clearance) {
  const FieldRect r = f.withBoundary();
  if (!(p.x >= r.x_min + clearance && p.x <= r.x_max - clearance &&
        p.y >= r.y_min + clearance && p.y <= r.y_max - clearance))
    return false;
  const double front = f.field_length / 2.0 + f.line_thickness / 2.0;
  const double back = front + f.goal_depth, gw = f.goal_width / 2.0;
  auto segment = [&](FieldMm a, FieldMm b) { return distanceToSegment(p, a, b); };
  for (double sx : {-1.0, 1.0}) {
    if (segment({sx * back, -gw}, {sx * back, gw}) < clearance ||
        segment({sx * front, gw}, {sx * back, gw}) < clearance ||
        segment({sx * front, -gw}, {sx * back, -gw}) < clearance)
      return false;
  }
  return true;
}

// Smallest distance between two points moving linearly over [0, duration].
double closestApproach(FieldMm a0, FieldMm va, FieldMm b0, FieldMm vb, double duration) {
  const double dx = a0.x - b0.x, dy = a0.y - b0.y;
  const double dvx = va.x - vb.x, dvy = va.y - vb.y;
  const double vv = dvx * dvx + dvy * dvy;
  double t = vv > 0 ? -(dx * dvx + dy * dvy) / vv : 0;
  t = std::clamp(t, 0.0, duration);
  return std::hypot(dx + dvx * t, dy + dvy * t);
}

}  // namespace

SceneCamera makeCamera(uint32_t id, const FieldPoint& position, const FieldPoint& look_at,
                       double focal_length, double distortion, ImagePx principal_offset,
                       uint32_t width, uint32_t height, const FieldPoint& up) {
  const Eigen::Vector3d c = vec(position);
  Eigen::Vector3d forward = vec(look_at) - c;
  if (!(forward.norm() > 1e-9)) throw std::invalid_argument("camera looks at its own position");
  forward.normalize();
  Eigen::Vector3d up_hint = vec(up);
  if (!(up_hint.norm() > 1e-12))
    up_hint = std::abs(forward.z()) > 0.95 ? Eigen::Vector3d(0, 1, 0) : Eigen::Vector3d(0, 0, 1);
  // Image rows grow downwards: the camera's y axis is minus the up hint made
  // orthogonal to the viewing direction; x = y cross z keeps it right-handed.
  Eigen::Vector3d image_up = up_hint - up_hint.dot(forward) * forward;
  if (!(image_up.norm() > 1e-9)) throw std::invalid_argument("camera 'up' is along its view");
  const Eigen::Vector3d y_axis = -image_up.normalized();
  const Eigen::Vector3d x_axis = y_axis.cross(forward);
  Eigen::Matrix3d field_to_camera;
  field_to_camera.row(0) = x_axis;
  field_to_camera.row(1) = y_axis;
  field_to_camera.row(2) = forward;
  SceneCamera cam;
  cam.calib = CameraCalibration::fromPose(id, focal_length, (width - 1) / 2.0 + principal_offset.u,
                                          (height - 1) / 2.0 + principal_offset.v, distortion,
                                          field_to_camera, c);
  cam.calib.image_width = width;
  cam.calib.image_height = height;
  return cam;
}

FieldMm robotPositionAt(const SceneRobot& r, double t) {
  return {r.position.x + r.velocity.x * t, r.position.y + r.velocity.y * t};
}

double robotOrientationAt(const SceneRobot& r, double t) {
  return std::remainder(r.orientation + r.angular_velocity * t, 2 * kPi);
}

namespace {

// Rolls the ball for dt seconds inside the box lo..hi of its center,
// reflecting the velocity component across each wall it meets.
void roll(BallState& s, double dt, const double lo[2], const double hi[2], double restitution) {
  double* p[2] = {&s.position.x, &s.position.y};
  double* v[2] = {&s.velocity.x, &s.velocity.y};
  // Bounded: a ball stuck in a corner with restitution near 1 cannot spin.
  for (int bounce = 0; bounce < 1000 && dt > 0; ++bounce) {
    double hit = dt;
    int axis = -1;
    for (int a = 0; a < 2; ++a) {
      double th = dt;
      // A ball already beyond a wall (placed outside) is not pulled back.
      if (*v[a] > 0 && *p[a] <= hi[a])
        th = (hi[a] - *p[a]) / *v[a];
      else if (*v[a] < 0 && *p[a] >= lo[a])
        th = (lo[a] - *p[a]) / *v[a];
      if (th < hit) hit = th, axis = a;
    }
    s.position.x += s.velocity.x * hit;
    s.position.y += s.velocity.y * hit;
    s.position.z += s.velocity.z * hit;
    dt -= hit;
    if (axis < 0) break;
    *v[axis] = -restitution * *v[axis];
  }
}

}  // namespace

BallState ballStateAt(const SceneBall& b, const FieldModel& field, double t) {
  BallState s{b.position, b.velocity};
  if (t <= 0) {
    s.position = {b.position.x + b.velocity.x * t, b.position.y + b.velocity.y * t,
                  b.position.z + b.velocity.z * t};
    return s;
  }
  const FieldRect walls = field.withBoundary();
  const double r = field.ball_radius;
  const double lo[2] = {walls.x_min + r, walls.y_min + r};
  const double hi[2] = {walls.x_max - r, walls.y_max - r};
  double now = 0;
  for (const BallKick& k : b.kicks) {
    if (k.t > t) break;
    roll(s, k.t - now, lo, hi, b.wall_restitution);
    s.velocity = k.velocity;
    now = k.t;
  }
  roll(s, t - now, lo, hi, b.wall_restitution);
  return s;
}

FieldPoint ballPositionAt(const SceneBall& b, const FieldModel& field, double t) {
  return ballStateAt(b, field, t).position;
}

bool ballMoves(const SceneBall& b) {
  auto moving = [](const FieldPoint& v) { return v.x != 0 || v.y != 0 || v.z != 0; };
  if (moving(b.velocity)) return true;
  for (const BallKick& k : b.kicks)
    if (moving(k.velocity)) return true;
  return false;
}

std::vector<SceneRobot> placeRandomRobots(const SceneSpec& scene, size_t camera_index, int yellow,
                                          int blue, uint64_t seed, double min_distance,
                                          double margin_px) {
  if (camera_index >= scene.cameras.size())
    throw std::invalid_argument("random robots: no camera " + std::to_string(camera_index));
  if (yellow < 0 || blue < 0 || yellow > 16 || blue > 16)
    throw std::invalid_argument("random robots: 0..16 robots per team");
  const CameraCalibration& calib = scene.cameras[camera_index].calib;
  const CameraModel cam(calib);
  SplitMix64 rng(mixSeed(seed, 0x526F626F74ull));
  std::vector<SceneRobot> out;
  for (int team = 0; team < 2; ++team) {
    // Distinct ids: the first n of a seeded shuffle of 0..15.
    std::array<int, 16> ids;
    std::iota(ids.begin(), ids.end(), 0);
    for (int i = 15; i > 0; --i) std::swap(ids[i], ids[rng.below(i + 1)]);
    // Ids already taken by the scene's own robots of this team go last.
    std::stable_partition(ids.begin(), ids.end(), [&](int id) {
      for (const SceneRobot& o : scene.robots)
        if (int(o.team) == team && o.id == id) return false;
      return true;
    });
    const int n = team == 0 ? yellow : blue;
    int taken = 0;
    for (const SceneRobot& o : scene.robots) taken += int(o.team) == team;
    if (n + taken > 16) throw std::invalid_argument("random robots: more than 16 in a team");
    for (int k = 0; k < n; ++k) {
      SceneRobot r;
      r.team = team == 0 ? Team::Yellow : Team::Blue;
      r.id = ids[k];
      bool placed = false;
      for (int attempt = 0; attempt < 5000 && !placed; ++attempt) {
        const ImagePx px{rng.uniform(margin_px, calib.image_width - 1 - margin_px),
                         rng.uniform(margin_px, calib.image_height - 1 - margin_px)};
        const auto p = cam.imageToField(px, r.height);
        if (!p || !insideWalls(scene.field, p->xy(), kWallClearance)) continue;
        bool clear = true;
        for (const SceneRobot& o : scene.robots)
          clear = clear && std::hypot(o.position.x - p->x, o.position.y - p->y) >= min_distance;
        for (const SceneRobot& o : out)
          clear = clear && std::hypot(o.position.x - p->x, o.position.y - p->y) >= min_distance;
        if (scene.ball.present)
          clear = clear && std::hypot(scene.ball.position.x - p->x, scene.ball.position.y - p->y) >=
                               min_distance;
        // Not under a hand or on a shoe: the box's footprint clear of the body.
        for (const SceneBox& b : scene.clutter)
          clear = clear && std::hypot(std::max({b.min.x - p->x, 0.0, p->x - b.max.x}),
                                      std::max({b.min.y - p->y, 0.0, p->y - b.max.y})) >= min_distance / 2 + 30;
        if (!clear) continue;
        r.position = p->xy();
        r.orientation = rng.uniform(-kPi, kPi);
        placed = true;
      }
      if (!placed) throw std::invalid_argument("random robots: cannot fit them in the camera view");
      out.push_back(r);
    }
  }
  return out;
}

namespace {

// The ball kicked at t = 0, then again (away from the robot) each time it
// would touch one. Returns false when no such course is found.
bool kickBallAround(SceneSpec& scene, double max_speed, double duration, SplitMix64& rng) {
  SceneBall& ball = scene.ball;
  // Ball center to robot center at contact, plus a little air.
  const double contact = kRobotRadius + scene.field.ball_radius + 20;
  constexpr double kStep = 0.001;  // s, the ball moves at most 6.5 mm per step
  constexpr int kMaxKicks = 40;
  auto kick = [&](double lo, double hi, FieldMm dir, double spread) {
    const double speed = rng.uniform(lo, hi) * max_speed, a = rng.uniform(-spread, spread);
    const double c = std::cos(a), s = std::sin(a);
    return FieldPoint{speed * (c * dir.x - s * dir.y), speed * (s * dir.x + c * dir.y), 0};
  };
  for (int attempt = 0; attempt < 100; ++attempt) {
    ball.kicks.clear();
    ball.velocity = kick(0.95, 1.0, {1, 0}, kPi);
    bool ok = true;
    // The whole last exposure lies before `duration`.
    for (int i = 0; ok && i * kStep <= duration; ++i) {
      const double t = i * kStep;
      const FieldMm p = ballPositionAt(ball, scene.field, t).xy();
      for (const SceneRobot& r : scene.robots) {
        const FieldMm q = robotPositionAt(r, t);
        if (std::hypot(p.x - q.x, p.y - q.y) >= contact) continue;
        // Kick one step before the touch, away from the robot.
        const double tk = t - kStep;
        if (tk <= 0 || (!ball.kicks.empty() && tk <= ball.kicks.back().t) ||
            int(ball.kicks.size()) == kMaxKicks) {
          ok = false;
          break;
        }
        const FieldMm b = ballPositionAt(ball, scene.field, tk).xy(), c = robotPositionAt(r, tk);
        const double d = std::hypot(b.x - c.x, b.y - c.y);
        const FieldMm away{(b.x - c.x) / d, (b.y - c.y) / d};
        FieldPoint v = kick(0.5, 1.0, away, kPi / 3);
        // It must leave the robot faster than the robot follows it.
        if ((v.x - r.velocity.x) * away.x + (v.y - r.velocity.y) * away.y < 0.25 * max_speed)
          v = kick(0.5, 1.0, away, 0);
        ball.kicks.push_back({tk, v});
        i = int(std::lround(tk / kStep));  // continue from the kick
        break;
      }
    }
    if (ok) return true;
  }
  ball.velocity = {};
  ball.kicks.clear();
  return false;
}

}  // namespace

void assignRandomMotion(SceneSpec& scene, double max_speed, double max_angular_speed,
                        double ball_max_speed, double duration, uint64_t seed) {
  SplitMix64 rng(mixSeed(seed, 0x4D6F7665ull));
  // Speeds between a quarter of the maximum and the maximum, so a motion
  // scene really has fast objects.
  auto randomVelocity = [&](double max) {
    const double speed = rng.uniform(0.25 * max, max), dir = rng.uniform(-kPi, kPi);
    return FieldMm{speed * std::cos(dir), speed * std::sin(dir)};
  };
  auto endInside = [&](FieldMm p, FieldMm v, double clearance) {
    return insideWalls(scene.field, {p.x + v.x * duration, p.y + v.y * duration}, clearance);
  };
  for (size_t i = 0; i < scene.robots.size(); ++i) {
    SceneRobot& r = scene.robots[i];
    r.velocity = {};
    r.angular_velocity = rng.uniform(-max_angular_speed, max_angular_speed);
    for (int attempt = 0; attempt < 50; ++attempt) {
      const FieldMm v = randomVelocity(max_speed);
      bool ok = endInside(r.position, v, kWallClearance);
      for (size_t j = 0; j < i && ok; ++j)
        ok = closestApproach(r.position, v, scene.robots[j].position, scene.robots[j].velocity,
                             duration) >= 200;
      if (ok) {
        r.velocity = v;
        break;
      }
    }
  }
  // Robots placed later may stand in the way of earlier movers: re-check and
  // stop those that would collide.
  for (size_t i = 0; i < scene.robots.size(); ++i)
    for (size_t j = 0; j < scene.robots.size(); ++j)
      if (i != j && closestApproach(scene.robots[i].position, scene.robots[i].velocity,
                                    scene.robots[j].position, scene.robots[j].velocity,
                                    duration) < 200)
        scene.robots[std::max(i, j)].velocity = {};
  if (scene.ball.present) kickBallAround(scene, ball_max_speed, duration, rng);
}

void scaleImages(SceneSpec& scene, double factor) {
  if (!(factor > 0)) throw std::invalid_argument("scale factor must be positive");
  for (SceneCamera& cam : scene.cameras) {
    CameraCalibration& c = cam.calib;
    const uint32_t w = std::max<uint32_t>(2, uint32_t(std::lround(c.image_width * factor)));
    const uint32_t h = std::max<uint32_t>(2, uint32_t(std::lround(c.image_height * factor)));
    const double sx = double(w) / c.image_width, sy = double(h) / c.image_height;
    const double s = 0.5 * (sx + sy);
    // Pixel (0, 0) covers [-0.5, 0.5]: edges scale, centers shift by half a pixel.
    c.principal_point_x = (c.principal_point_x + 0.5) * sx - 0.5;
    c.principal_point_y = (c.principal_point_y + 0.5) * sy - 0.5;
    c.focal_length *= s;
    c.image_width = w, c.image_height = h;
  }
}

SceneSpec defaultScene() {
  SceneSpec s;
  s.name = "default";
  s.seed = 1;
  s.field = FieldModel::divisionB();
  // Over the center of the negative half (incl. boundary), image width along
  // the field width.
  s.cameras.push_back(makeCamera(0, {-2250, 0, 5000}, {-2250, 0, 0}, 875, 0.03, {0, 0}, 1224,
                                 1024, {-1, 0, 0}));
  s.ball.position = {-1800, 400, 21.5};
  s.robots = placeRandomRobots(s, 0, 6, 6, s.seed);
  s.frames = 5;
  s.fps = 60;
  assignRandomMotion(s, 1500, 2, 3000, s.frames / s.fps, s.seed);
  return s;
}

}  // namespace dv
