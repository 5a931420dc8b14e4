// End to end on rendered frames: renderer -> CPU pixel pipeline -> detector,
// compared with the renderer's truth, at the presets' full 2448 x 2048 and
// at half that (same pose, half the focal length), with the same defaults,
// with few frames per condition to keep the suite fast. Set DV_SCENE_FULL=1 to run
// more frames per condition (for the report).
#include <gtest/gtest.h>

#include <string>

#include "scene_scoring.h"

namespace dv {
namespace {

using test::SceneScore;
using test::fullRun;
using test::halveResolution;
using test::score;

// Top-down half field, 11 + 11 robots at random ids and a ball, new random
// placements per frame, each frame alone; the bars.
void expectTopDownBars(bool half_resolution, const char* name) {
  SceneScore s;
  const int placements = fullRun() ? 12 : 2;
  for (int k = 0; k < placements; ++k) {
    SceneSpec spec = presetScene("top_down_div_b_half");
    if (half_resolution) halveResolution(spec);
    spec.seed = 100 + k;
    spec.robots.clear();
    spec.robots = placeRandomRobots(spec, 0, 11, 11, spec.seed, 200, 30);
    score(spec, 1, true, s);
  }
  std::printf("%s\n", s.summary(name).c_str());
  EXPECT_GE(s.recall(), 0.99);
  EXPECT_GE(s.precision(), 0.99);
  EXPECT_GE(s.idAccuracy(), 0.99);
  EXPECT_LE(SceneScore::median(s.pos_err), 0.7);
  // The orientation bar is for 2448 x 2048 (1224: 0.25 deg median).
  if (!half_resolution) {
    EXPECT_LE(SceneScore::median(s.ang_err) * 180 / kPi, 0.3);
  }
  EXPECT_GE(s.ballRecall(), 0.99);
  EXPECT_LE(SceneScore::median(s.ball_err), 3.0);
}

TEST(DetectionScene, TopDownHalfFieldEachFrameAlone) { expectTopDownBars(false, "top_down"); }

// The same at 1224 x 1024 (same pose, half the focal length): the shipped
// defaults must serve both resolutions. This camera's 2x2 Bayer cells cover
// 11 mm of field, so it is sampled at every pixel (bayer_sampling.h); with
// 2x2 subsampling recall was 0.977 over the 12 placements of DV_SCENE_FULL=1.
TEST(DetectionScene, TopDownHalfResolutionEachFrameAlone) {
  expectTopDownBars(true, "top_down 1224x1024");
}

class HarshScenes : public ::testing::TestWithParam<const char*> {};

// A preset's own placement, then new random placements of as many robots,
// each frame alone.
SceneScore scorePlacements(const std::string& preset, int placements, bool half_resolution) {
  SceneScore s;
  for (int k = 0; k < placements; ++k) {
    SceneSpec spec = presetScene(preset);
    if (half_resolution) halveResolution(spec);
    if (k > 0) {
      spec.seed += k;
      const int n = static_cast<int>(spec.robots.size()) / 2;
      spec.robots.clear();
      spec.robots = placeRandomRobots(spec, 0, n, n, spec.seed, 200, 30);
    }
    score(spec, 1, true, s);
  }
  return s;
}

TEST_P(HarshScenes, RobotsAndBallWithTheSameDefaults) {
  const SceneScore s = scorePlacements(GetParam(), fullRun() ? 6 : 1, false);
  std::printf("%s\n", s.summary(GetParam()).c_str());
  EXPECT_GE(s.precision(), 0.98);
  EXPECT_GE(s.ballPrecision(), 0.98);
  EXPECT_GE(s.detectableRecall(), 0.97);
  EXPECT_GE(s.detectableBallRecall(), 0.97);
  // The overall bar, the side view included: its robot recall is
  // 0.983 (59 of 60) over the 6 placements of DV_SCENE_FULL=1, every one
  // with the right id, precision 1.000 (recall 0.967 before a center and two
  // side blobs could take markers read from the frame at the other two
  // slots; 0.933 with 4 wrong ids before that; 0.750 before the whitened
  // gradient and the border rules, 0.72 before weak peaks). Its far side
  // blobs (4.8..7.1 m away, 2-4 pixels tall) are stretched along the viewing
  // direction, at any angle on the grid; the gradient is whitened there
  // (pipeline/view_stretch.h), and their positions, up to 15 mm off along
  // the ray (a pixel there covers 17 mm of field along it, 4 mm across), fit
  // with the tolerance stretched along the ray (pattern_fit.h; one more
  // robot). A side slot with no peak, cut by the image border or one or two
  // pixels tall, takes the marker the frame shows there
  // (detection/seen_color.h): the 4 robots that had a guessed, wrong id and
  // one robot cut by the border now have the right one. Of the 2 lost before
  // the two-side patterns (one is found now; which one was not checked): one
  // cut by the border with a side dot wholly outside the image (one of two
  // ids, not reported), and one 7.1 m away, its dots 1.7-1.8 px tall: its
  // two pink side dots make no peak (score -0.03), and the two green ones
  // are a diagonal pair that fits two placements 90 degrees apart, at both
  // of which the frame's color at the other two slots reads pink (one of two
  // ids, so not taken).
  EXPECT_GE(s.recall(), 0.97);
  EXPECT_GE(s.idAccuracy(), 0.99);
  EXPECT_GE(s.ballRecall(), 0.97);
}

INSTANTIATE_TEST_SUITE_P(Presets, HarshScenes,
                         ::testing::Values("uneven_light", "blue_white_balance", "dark_noisy",
                                           "gray_carpet", "side_view"));

class HarshScenesHalfResolution : public ::testing::TestWithParam<const char*> {};

TEST_P(HarshScenesHalfResolution, RobotsAndBallWithTheSameDefaults) {
  const SceneScore s = scorePlacements(GetParam(), fullRun() ? 6 : 3, true);
  std::printf("%s\n", s.summary(std::string(GetParam()) + " 1224x1024").c_str());
  // Dark and noisy at this resolution: its side blobs are both blurred and
  // noisy and score around the threshold, and a lower threshold lets noise
  // blobs through (0.21: recall 0.96, precision 0.97). The renderer's noise
  // is per pixel, so at half the resolution each millimetre of field holds a
  // quarter of the samples, and twice the noise, of 2448 x 2048. Taken as
  // weak peaks only where a pattern of blobs predicts them
  // (detection/weak_sides.h), they give recall 1.00, precision 1.00 over
  // the 6 placements of DV_SCENE_FULL=1, and with a missing side's color
  // read from the frame (detection/seen_color.h) id 1.00 (0.99 before;
  // blobs alone: recall 0.90, id 0.90, with robots missing a side blob
  // reported with a guessed id, right in 24 of 33).
  EXPECT_GE(s.recall(), 0.97);
  EXPECT_GE(s.idAccuracy(), 0.97);
  EXPECT_GE(s.precision(), 0.98);
  EXPECT_GE(s.ballRecall(), 0.97);
  EXPECT_GE(s.ballPrecision(), 0.98);
}

INSTANTIATE_TEST_SUITE_P(Presets, HarshScenesHalfResolution,
                         ::testing::Values("uneven_light", "blue_white_balance", "dark_noisy", "gray_carpet"));

// 60 fps, 100 Hz flicker, 8 ms motion blur, robots at up to 3 m/s turning
// at up to 4 rad/s, tracked. The preset's ball is kicked at 6.1-6.5 m/s and
// bounces off the walls; over the exposure it is a streak of up to 52 mm
// whose round blob score falls with speed (alone in the frame: 0.75 at rest,
// 0.58 at 3 m/s, 0.42 at 4 m/s, 0.25 at 5 m/s, no peak at 6.5 m/s; the
// threshold is 0.24). The fast-ball pass (pipeline/streak_score.h) finds
// it as a streak at its mid-exposure position: ball recall 0.43 -> 1.00 over
// the 60 frames of DV_SCENE_FULL=1, precision 1.00, median error 2.1 mm.
// The bars for tracked motion that both motion tests hold.
void expectTrackedRobotBars(const SceneScore& s) {
  EXPECT_GE(s.recall(), 0.98);
  EXPECT_GE(s.precision(), 0.98);
  EXPECT_GE(s.idAccuracy(), 0.98);
  EXPECT_GE(s.ballPrecision(), 0.98);
}

TEST(DetectionScene, MotionWithFlickerAndBlurTracked) {
  SceneSpec spec = presetScene("motion_60fps_flicker");
  spec.motion_blur_samples = fullRun() ? spec.motion_blur_samples : 3;
  SceneScore s;
  score(spec, fullRun() ? spec.frames : 8, false, s);
  std::printf("%s\n", s.summary("motion_60fps_flicker").c_str());
  expectTrackedRobotBars(s);
  EXPECT_GE(s.ballRecall(), 0.98);
  EXPECT_LE(SceneScore::median(s.ball_err), 5.0);
}

// The same motion at 1224 x 1024 with the ball kicked at up to 4 m/s, where
// its streak still scores as a blob: every bar of the issue holds.
TEST(DetectionScene, MotionBallAt4MetresPerSecondHalfResolutionTracked) {
  SceneSpec spec = presetScene("motion_60fps_flicker");
  halveResolution(spec);
  assignRandomMotion(spec, 3000, 4, 4000, spec.frames / spec.fps, spec.seed);
  spec.motion_blur_samples = fullRun() ? spec.motion_blur_samples : 3;
  SceneScore s;
  score(spec, fullRun() ? spec.frames : 12, false, s);
  std::printf("%s\n", s.summary("motion_60fps_flicker 4 m/s ball 1224x1024").c_str());
  expectTrackedRobotBars(s);
  EXPECT_GE(s.ballRecall(), 0.98);
}

}  // namespace
}  // namespace dv
