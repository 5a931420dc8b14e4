#pragma once
// The top-down half field varied one condition at a time, shared by the
// sweeps (scene_sweep_test.cpp: carpets, poses, lenses, sensor, crowds;
// scene_color_sweep_test.cpp: color casts, marker and ball shades).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <functional>
#include <string>
#include <vector>

#include "detection/pattern_fit.h"
#include "scene_scoring.h"

namespace dv::test {

constexpr int kWidth = 2448, kHeight = 2048;
const FieldPoint kTarget{-2250, 0, 0};  // the preset's view center

// A camera's color cast: its white balance gains, saturation and gamma.
inline void cast(SceneSpec& s, Rgb white_balance, double saturation = 1, double gamma = 1) {
  s.lighting.white_balance = white_balance;
  s.lighting.saturation = saturation;
  s.lighting.gamma = gamma;
}

const Rgb kTungsten{1.6, 1.0, 0.6}, kColdLed{0.7, 1.0, 1.7};

// A camera `height` mm above the ground looking at the preset's view center
// with `tilt` rad from the vertical, its view turned by `yaw` rad.
inline SceneCamera tiltedCamera(double height, double tilt, double yaw, double focal, double distortion,
                         ImagePx offset = {6.5, -4.0}) {
  const double back = height * std::tan(tilt);
  const FieldPoint pos{kTarget.x - back * std::cos(yaw), kTarget.y - back * std::sin(yaw), height};
  // Straight down, image up is the yaw direction; tilted, image up is +z.
  const FieldPoint up = tilt < 1e-6 ? FieldPoint{std::cos(yaw), std::sin(yaw), 0} : FieldPoint{};
  return makeCamera(0, pos, kTarget, focal, distortion, offset, kWidth, kHeight, up);
}

// The pattern colors of one league (all four at once).
inline void patternColors(SceneSpec& s, Rgb yellow, Rgb blue, Rgb green, Rgb pink) {
  s.materials.yellow = yellow, s.materials.blue = blue;
  s.materials.green = green, s.materials.pink = pink;
}

// Robots with fresh ids (per team, in order) at the given places; the rest of
// the 11 + 11 are placed at random by the caller.
struct Crowd {
  SceneSpec& spec;
  int next[2] = {0, 0};
  void add(Team team, FieldMm p, double orientation) {
    SceneRobot r;
    r.team = team;
    r.id = next[team == Team::Yellow ? 0 : 1]++ * 3 % 16;  // 0, 3, 6, ... distinct
    r.position = p;
    r.orientation = orientation;
    spec.robots.push_back(r);
  }
};

// A robot at `p` facing `orientation`, and the ball at `distance` mm from
// its center in direction `bearing` (robot frame, 0 = straight ahead).
inline void ballBeside(SceneSpec& s, FieldMm p, double orientation, double bearing, double distance) {
  Crowd c{s};
  c.add(Team::Blue, p, orientation);
  const double a = orientation + bearing;
  s.ball.present = true;
  s.ball.position = {p.x + distance * std::cos(a), p.y + distance * std::sin(a), 21.5};
}

struct Condition {
  const char* name;
  // Changes the preset at 2448 x 2048 for placement k (0-based).
  std::function<void(SceneSpec&, int k)> apply;
};

// Rule-limit ball positions: at most 20 % of the ball covered from above.
inline double ballOutside(const SceneSpec& s) { return minBallOutsideDistance(s.field.ball_radius) + 0.5; }

// Placement k of a condition at full or half resolution, with or without
// the ball.
inline SceneSpec conditionScene(const Condition& c, int k, bool half, bool ball = true) {
  SceneSpec s = presetScene("top_down_div_b_half");
  s.seed = 300 + 17 * k;
  s.robots.clear();
  c.apply(s, k);
  s.ball.present = ball;
  if (half) test::halveResolution(s);
  int taken[2] = {0, 0};
  for (const auto& r : s.robots) ++taken[r.team == Team::Yellow ? 0 : 1];
  // Whole patterns in view with room for the blob windows (about 130 mm at
  // the image edge).
  const double margin = 40.0 * s.cameras[0].calib.image_width / 1224;
  const auto more = placeRandomRobots(s, 0, std::max(0, 11 - taken[0]), std::max(0, 11 - taken[1]),
                                     s.seed, 200, margin);
  s.robots.insert(s.robots.end(), more.begin(), more.end());
  return s;
}

inline void printRow(const char* name, const char* res, const SceneScore& s) {
  std::printf("| %-26s | %s | %4d | %.3f | %.3f | %.3f | %.3f | %.3f | %3d | %.3f | %.3f |\n", name,
              res, s.truth_robots, s.recall(), s.precision(), s.idAccuracy(), s.detectableRecall(),
              s.fullPatternIdAccuracy(), s.truth_balls, s.ballRecall(), s.ballPrecision());
  if (std::getenv("DV_MISSES") && !s.ball_err.empty()) {
    std::vector<double> e = s.ball_err;
    std::sort(e.begin(), e.end());
    std::printf("  ball error: median %.2f mm, largest %.2f mm\n", e[e.size() / 2], e.back());
  }
}

// Scores a condition (one placement at 1224 x 1024; DV_SCENE_FULL=1: 4 at
// both sizes), prints its table rows and holds it to the sweeps' bars.
// Columns: robots, recall, precision, id accuracy, recall of robots whose
// center and 4 side blobs reached the detector, id accuracy of robots with
// all 4 side blobs, balls, ball recall, ball precision.
inline void sweepCondition(const Condition& c) {
  const int placements = fullRun() ? 4 : 1;
  for (bool half : {true, false}) {
    if (!half && !fullRun()) continue;
    SceneScore s, without_ball;
    for (int k = 0; k < placements; ++k) {
      score(conditionScene(c, k, half), 1, true, s);
      // The same placement without the ball (most cameras' frames): a
      // round ball outranks the false ones a frame may hold, and hides them.
      score(conditionScene(c, k, half, false), 1, true, without_ball);
    }
    printRow(c.name, half ? "1224x1024" : "2448x2048", s);
    if (without_ball.balls_detected > 0)
      std::printf("  without the ball: %d false balls in %d frames\n", without_ball.balls_detected, placements);
    SCOPED_TRACE(std::string(c.name) + (half ? " 1224x1024" : " 2448x2048"));
    EXPECT_LE(without_ball.balls_detected, 0.02 * placements) << "false balls in frames without the ball";
    // The bars, at both sizes: recall 0.99 with the right team and
    // id, precision 0.995, ball recall 0.99, at most 0.02 false balls per
    // frame (one ball per frame here).
    EXPECT_GE(s.recall(), 0.99);
    EXPECT_GE(s.idAccuracy(), 0.99);
    EXPECT_GE(s.precision(), 0.995);
    EXPECT_GE(s.detectableRecall(), 0.99);
    EXPECT_GE(s.fullPatternIdAccuracy(), 0.99);
    EXPECT_GE(s.ballRecall(), 0.99);
    EXPECT_GE(s.ballPrecision(), 0.98);
  }
}

// A gtest name for a condition: its name with every other character as '_'.
inline std::string conditionTestName(std::string n) {
  for (char& ch : n)
    if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
  return n;
}

}  // namespace dv::test
