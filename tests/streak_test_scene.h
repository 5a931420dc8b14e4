#pragma once
// A lone ball rolling straight under the motion preset's camera (its height,
// focal length, 8 ms exposure, motion blur, flicker and noise), seen by a
// small camera centered on where the ball is at the middle of frame 3's
// exposure: the scene of the fast-ball tests.
#include <cmath>

#include "geometry/camera_model.h"
#include "synth/scene.h"

namespace dv::test {

inline constexpr int kStreakFrame = 3;

inline SceneSpec streakScene(double speed, double angle, int width = 768, int height = 640) {
  SceneSpec spec = presetScene("motion_60fps_flicker");
  spec.robots.clear();
  const auto& big = spec.cameras.at(0).calib;
  const double cam_z = CameraModel(big).position().z();
  spec.ball = SceneBall{};
  spec.ball.position = {-2400, -150, 21.5};
  spec.ball.velocity = {speed * std::cos(angle), speed * std::sin(angle), 0};
  const double t = kStreakFrame / spec.fps;
  const FieldPoint mid{spec.ball.position.x + spec.ball.velocity.x * t,
                       spec.ball.position.y + spec.ball.velocity.y * t, 0};
  spec.cameras = {makeCamera(0, {mid.x + 30, mid.y - 20, cam_z}, {mid.x + 30, mid.y - 20, 0}, big.focal_length,
                             big.distortion, {0, 0}, width, height)};
  spec.frames = kStreakFrame + 1;
  return spec;
}

}  // namespace dv::test
