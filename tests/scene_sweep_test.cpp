// Conditions the scene presets do not cover, one at a time on the top-down
// half field (11 + 11 robots at random ids and a ball, each frame alone):
// carpets, pattern and robot-top colors, camera height, tilt, yaw, lens,
// exposure, white balance, noise, vignetting, light gradients, crowded
// robots, the ball beside, in front of and partly under robots and on lines,
// the Division A field, RGB input (also through JPEG) and all four Bayer
// layouts. Every condition runs with the shipped defaults at 1224 x 1024
// (one placement, the CI variant); DV_SCENE_FULL=1 runs 4 placements each
// at 1224 x 1024 and at 2448 x 2048 and prints one table row per condition
// and resolution.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "scene_conditions.h"

namespace dv {
namespace {

using namespace dv::test;

const std::vector<Condition>& conditions() {
  static const std::vector<Condition> list = {
      {"nominal", [](SceneSpec&, int) {}},
      // --- carpets
      {"carpet_dark_green", [](SceneSpec& s, int) { s.materials.carpet = {18, 62, 26}; }},
      {"carpet_light_green", [](SceneSpec& s, int) { s.materials.carpet = {100, 170, 95}; }},
      {"carpet_blue_green", [](SceneSpec& s, int) { s.materials.carpet = {25, 100, 105}; }},
      {"carpet_worn",
       [](SceneSpec& s, int) {
         s.materials.carpet = {78, 108, 66};
         s.materials.carpet_texture = 0.28;
       }},
      // --- pattern and robot colors
      {"colors_saturated",
       [](SceneSpec& s, int) { patternColors(s, {255, 235, 0}, {0, 45, 235}, {0, 235, 40}, {255, 30, 150}); }},
      {"colors_pale",
       [](SceneSpec& s, int) {
         patternColors(s, {240, 230, 130}, {110, 145, 225}, {140, 225, 150}, {245, 160, 205});
       }},
      {"colors_hues_warm",  // yellow toward orange, blue toward cyan, green toward lime
       [](SceneSpec& s, int) {
         patternColors(s, {245, 185, 25}, {30, 120, 225}, {130, 215, 50}, {235, 70, 130});
       }},
      {"colors_hues_cool",  // yellow toward lime, blue toward violet, pink toward magenta
       [](SceneSpec& s, int) {
         patternColors(s, {210, 225, 50}, {70, 60, 210}, {40, 200, 130}, {220, 70, 230});
       }},
      {"robot_top_gray", [](SceneSpec& s, int) { s.materials.robot_top = {75, 75, 78}; }},
      // --- camera pose and lens
      {"height_3m", [](SceneSpec& s, int) { s.cameras = {tiltedCamera(3000, 0, kPi, 1750, 0.03)}; }},
      {"height_6m", [](SceneSpec& s, int) { s.cameras = {tiltedCamera(6000, 0, kPi, 1750, 0.03)}; }},
      {"yaw_37deg_top_down",
       [](SceneSpec& s, int) { s.cameras = {tiltedCamera(5000, 0, 0.65, 1750, 0.03)}; }},
      {"tilt_15deg_yaw_100",
       [](SceneSpec& s, int) { s.cameras = {tiltedCamera(4500, 0.26, 1.75, 1750, 0.03)}; }},
      {"tilt_25deg_yaw_-60",
       [](SceneSpec& s, int) { s.cameras = {tiltedCamera(4500, 0.44, -1.05, 1750, 0.03)}; }},
      {"tilt_35deg_yaw_200",
       [](SceneSpec& s, int) { s.cameras = {tiltedCamera(4000, 0.61, 3.5, 1750, 0.03)}; }},
      {"distortion_-0.15",
       [](SceneSpec& s, int) { s.cameras = {tiltedCamera(5000, 0, kPi, 1750, -0.15)}; }},
      {"distortion_+0.10",
       [](SceneSpec& s, int) { s.cameras = {tiltedCamera(5000, 0, kPi, 1750, 0.10)}; }},
      {"principal_offset",
       [](SceneSpec& s, int) { s.cameras = {tiltedCamera(5000, 0, kPi, 1750, 0.03, {90, -70})}; }},
      {"focal_short",
       [](SceneSpec& s, int) { s.cameras = {tiltedCamera(4500, 0, kPi, 1300, 0.05)}; }},
      {"focal_long",
       [](SceneSpec& s, int) { s.cameras = {tiltedCamera(5500, 0, kPi, 2300, 0.02)}; }},
      // --- exposure, white balance, sensor
      {"exposure_low_gain_noise",
       [](SceneSpec& s, int) {
         s.lighting.exposure = 0.45;
         s.noise_sigma = 3.0;
         s.shot_noise = 0.12;
       }},
      {"exposure_bright_clipping", [](SceneSpec& s, int) { s.lighting.exposure = 1.6; }},
      {"white_balance_warm", [](SceneSpec& s, int) { s.lighting.white_balance = {1.35, 1.0, 0.7}; }},
      {"white_balance_green", [](SceneSpec& s, int) { s.lighting.white_balance = {0.85, 1.2, 0.8}; }},
      {"noise_high",
       [](SceneSpec& s, int) {
         s.noise_sigma = 4.0;
         s.shot_noise = 0.25;
       }},
      {"lens_blur", [](SceneSpec& s, int) { s.lens_blur_px = 1.2; }},
      {"vignetting", [](SceneSpec& s, int) { s.lighting.vignetting = 0.6; }},
      {"dark_object_shadows", [](SceneSpec& s, int) { s.lighting.object_shadow = 0.9; }},
      {"light_gradient_patches",
       [](SceneSpec& s, int) {
         s.lighting.uneven_ratio = 4.0;
         s.lighting.uneven_direction = 2.3;
         s.lighting.sun_patches = {{{-1000, -1500}, 700, 400, 0.3, 1.7, 0.2},
                                   {{-3600, 1800}, 500, 900, -0.5, 1.5, 0.4}};
         s.lighting.shadows = {{{-2800, 0}, 1500, 400, 1.2, 0.6, 0.5}};
       }},
      // --- crowding and the ball
      {"robots_touching",
       [](SceneSpec& s, int k) {
         Crowd c{s};
         const double a = 0.7 * k;
         // A row of three touching robots, a touching pair, one at each wall.
         for (int i = 0; i < 3; ++i)
           c.add(i % 2 ? Team::Yellow : Team::Blue, {-3000.0 + 180 * i, -1200}, a + i);
         c.add(Team::Yellow, {-1500, 1000}, a + 2);
         c.add(Team::Blue, {-1500 + 180 * std::cos(a), 1000 + 180 * std::sin(a)}, a - 1);
         c.add(Team::Yellow, {-2600, 3300 - 90}, a + 0.5);
         c.add(Team::Blue, {-2000, -3300 + 90}, -a);
         c.add(Team::Yellow, {-4800 + 90, -2200}, a + 3);
       }},
      {"crowd_16_16",  // both full teams in one camera, bodies nearly touching
       [](SceneSpec& s, int k) {
         s.robots = placeRandomRobots(s, 0, 16, 16, 900 + k, 185, 80);
       }},
      {"ball_touching_robot",
       [](SceneSpec& s, int k) {
         // In front of the kicker (flat front 55 mm), or against the side.
         const double bearing = k % 2 ? 1.4 : 0.0;
         const double d = (k % 2 ? 85.0 : 55.0) + s.field.ball_radius + 1;
         ballBeside(s, {-2400, 500}, 0.9 * k - 1.0, bearing, d);
       }},
      {"ball_under_robot_edge",
       [](SceneSpec& s, int k) {
         // 20 % of the ball under the robot's top (the rule's limit), in the
         // dribbler or at the side, on the side facing the camera: on the far
         // side the robot's body hides most of the rest (parallax).
         const FieldMm p{-1800.0 + 250 * k, -900.0 + 400 * (k % 3)};
         const Eigen::Vector3d c = CameraModel(s.cameras[0].calib).position();
         const double to_camera = std::atan2(c.y() - p.y, c.x() - p.x);
         const double bearing = k % 2 ? -1.6 : 0.0;
         const double d = (k % 2 ? 85.0 : 55.0) + ballOutside(s);
         ballBeside(s, p, to_camera - bearing, bearing, d);
       }},
      {"ball_on_lines",
       [](SceneSpec& s, int k) {
         // Penalty line, penalty corner (a crossing), touch line, goal
         // line, halfway line, center circle.
         static const std::array<FieldMm, 6> kOnLine = {
             {{-3500, 300}, {-3500, 1000}, {-2000, -3000}, {-4500, -1800}, {0, 800}, {-420, -277}}};
         s.ball.position = {kOnLine[k % 6].x, kOnLine[k % 6].y, 21.5};
       }},
      // --- field, input format
      {"division_a",
       [](SceneSpec& s, int) {
         s.field = FieldModel::divisionA();
         s.cameras = {makeCamera(0, {-3000, -2250, 6000}, {-3000, -2250, 0}, 1900, 0.03, {4, 3},
                                 kWidth, kHeight, {-1, 0, 0})};
         s.ball.position = {-4000, -1500, 21.5};
       }},
      {"rgb_input", [](SceneSpec& s, int) { s.bayer = false; }},
      // A camera streaming JPEG: chroma at half resolution, 8x8 blocks. At
      // 1224 x 1024 a chroma sample covers 11.4 mm: a green dot's chroma
      // runs over its 5 mm black ring into the carpet (same chromaticity,
      // only brighter): of the 172 green dots of the 4 placements, 36 (q90)
      // and 75 (q60) score under the weak threshold (none without JPEG, nor
      // any pink dot), while the frame still shows the dot's color at the
      // slot; the block ringing makes dark peaks on the robot top. The
      // detector takes a center and two side blobs whose other slots show
      // markers in the frame, and no peak much darker than the center as a
      // side blob (q90 recall 0.966 -> 1.000, q60 0.886 -> 1.000, id
      // 0.974 -> 1.000).
      {"jpeg_q90", [](SceneSpec& s, int) { s.bayer = false, s.jpeg_quality = 90; }},
      {"jpeg_q60", [](SceneSpec& s, int) { s.bayer = false, s.jpeg_quality = 60; }},
      {"bayer_grbg", [](SceneSpec& s, int) { s.bayer_layout = BayerLayout::GRBG; }},
      {"bayer_gbrg", [](SceneSpec& s, int) { s.bayer_layout = BayerLayout::GBRG; }},
      {"bayer_bggr", [](SceneSpec& s, int) { s.bayer_layout = BayerLayout::BGGR; }},
  };
  return list;
}

class SceneSweep : public ::testing::TestWithParam<size_t> {};

// The bars (sweepCondition, scene_conditions.h), and why:
//  - what the detector is answerable for: no false robots or balls, every
//    robot whose blobs arrived found, every fully seen pattern identified;
//  - every ball (4 placements of DV_SCENE_FULL=1, each one ball). A ball
//    touching a robot on the side away from the camera, part of it hidden
//    by the robot's edge, left no round blob above the threshold (0.75 at
//    both sizes); the fast-ball pass (pipeline/streak_score.h) finds what
//    is left of it (1.00). The clipped ball at 1224 x 1024 (0.25 before
//    clipped_color.h) is found in all 4;
//  - overall recall also depends on the pixel stage delivering the side
//    blobs. At 1224 x 1024 a Bayer cell is 11.4 mm and green side blobs,
//    which meet the green carpet at the robot's rim, often score just below
//    the blob threshold, and pale pink ones too; the detector takes them as
//    weak peaks where a pattern of blobs predicts them (weak_sides.h), and
//    a center with two side blobs where the frame shows markers at the
//    other two slots (hypothesis_search.cpp, completeFromTwoSides). Over
//    the 4 placements of DV_SCENE_FULL=1 the lowest recall is 0.989 (25°
//    tilt; 0.852 before weak peaks, 0.909 before markers read from the
//    frame), every other condition 1.000 at both sizes (pale colors 0.807
//    before weak peaks); 1.000 in the one CI placement of the 25° tilt
//    (0.818 before).
TEST_P(SceneSweep, SameDefaultsHoldOutsideThePresets) { sweepCondition(conditions()[GetParam()]); }

// An outsider's directory of independent scenes is played as a 60 fps
// sequence: history from one scene must not give robots of the next scene
// the identities of those that stood there before.
TEST(SceneSweepSequence, IndependentScenesAsOneSequenceScoreAsFramesAlone) {
  const Condition* crowd = nullptr;  // 16 + 16 robots: chance meetings are frequent
  for (const auto& c : conditions())
    if (std::string(c.name) == "crowd_16_16") crowd = &c;
  ASSERT_NE(crowd, nullptr);
  const int frames = fullRun() ? 12 : 6;
  std::unique_ptr<Detector> tracked, alone;
  std::unique_ptr<CpuPipeline> pipeline;
  SceneScore with_history, without;
  for (int k = 0; k < frames; ++k) {
    const SceneSpec spec = conditionScene(*crowd, k, true);
    const CameraModel cam(spec.cameras[0].calib);
    if (!pipeline) {
      PipelineOptions popt;
      popt.bayer = test::pipelineBayer(spec);
      pipeline = std::make_unique<CpuPipeline>(cam, spec.field, popt);
      tracked = std::make_unique<Detector>(cam, spec.field, DetectorOptions{});
      DetectorOptions single;
      single.tracking = false;
      alone = std::make_unique<Detector>(cam, spec.field, single);
    }
    const RenderedFrame frame = Renderer(spec).render(0, 0);
    BlobList blobs;
    ASSERT_TRUE(pipeline->process(frame.image, blobs));
    Detections a, b;
    tracked->process(blobs, k / 60.0, a);
    alone->process(blobs, k / 60.0, b);
    ASSERT_EQ(a.robots.size(), b.robots.size()) << "scene " << k;
    for (size_t i = 0; i < a.robots.size(); ++i) {
      EXPECT_EQ(a.robots[i].team, b.robots[i].team) << "scene " << k;
      EXPECT_EQ(a.robots[i].id, b.robots[i].id) << "scene " << k;
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Conditions, SceneSweep, ::testing::Range<size_t>(0, conditions().size()),
                         [](const ::testing::TestParamInfo<size_t>& info) {
                           return conditionTestName(conditions()[info.param].name);
                         });

}  // namespace
}  // namespace dv
