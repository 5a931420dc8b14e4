// A robot's orientation read along the ring its side dots lie on
// (detection/ring_orientation.h), on rendered frames: the truth's, to a
// degree, for robots of every id, also where the dots are pale; none on
// the bare carpet, where no dots make bright arcs.
#include <gtest/gtest.h>

#include <cmath>

#include "detection/ring_orientation.h"
#include "scene_scoring.h"

namespace dv {
namespace {

// Worst orientation error (deg) over the robots of the top-down half field
// at 1224 x 1024 (light: a scene edit); how many robots gave none.
void readRobots(void (*light)(SceneSpec&), double& worst_deg, int& none, int& robots) {
  SceneSpec spec = presetScene("top_down_div_b_half");
  if (light) light(spec);
  test::halveResolution(spec);
  spec.robots.clear();
  spec.robots = placeRandomRobots(spec, 0, 8, 8, 11, 200, 30);
  Renderer renderer(spec);
  const CameraModel cam(spec.cameras[0].calib);
  const RenderedFrame frame = renderer.render(0, 0);
  const FrameView view{&frame.image, test::pipelineBayer(spec)};
  worst_deg = 0, none = 0, robots = 0;
  for (const auto* list : {&frame.truth.robots_yellow(), &frame.truth.robots_blue()})
    for (const auto& t : *list) {
      ++robots;
      const auto o = ringOrientation(view, cam, {t.x(), t.y(), t.height()}, 0);
      if (!o) {
        ++none;
        continue;
      }
      worst_deg = std::max(worst_deg, std::abs(std::remainder(*o - t.orientation(), 2 * kPi)) * 180 / kPi);
    }
}

TEST(RingOrientation, ReadsEveryRobotToADegree) {
  double worst;
  int none, robots;
  readRobots(nullptr, worst, none, robots);
  EXPECT_EQ(robots, 16);
  EXPECT_EQ(none, 0);
  EXPECT_LT(worst, 1.5);
}

// Pale pink under a magenta cast, over-exposed: the dots' chroma is gone,
// their brightness is not.
TEST(RingOrientation, PaleDotsStillMakeBrightArcs) {
  double worst;
  int none, robots;
  readRobots(
      [](SceneSpec& s) {
        s.lighting.white_balance = {1.2, 0.8, 1.2};
        s.lighting.exposure = 1.6;
        s.materials.pink = {250, 175, 205};
      },
      worst, none, robots);
  EXPECT_EQ(none, 0);
  EXPECT_LT(worst, 1.5);
}

TEST(RingOrientation, NoneOnTheCarpetOrOutsideTheImage) {
  SceneSpec spec = presetScene("top_down_div_b_half");
  test::halveResolution(spec);
  spec.robots.clear();
  Renderer renderer(spec);
  const CameraModel cam(spec.cameras[0].calib);
  const RenderedFrame frame = renderer.render(0, 0);
  const FrameView view{&frame.image, test::pipelineBayer(spec)};
  int found = 0;
  for (double x = -4000; x <= -500; x += 500)
    for (double y = -2500; y <= 2500; y += 500) found += ringOrientation(view, cam, {x, y, 140}, 0).has_value();
  EXPECT_EQ(found, 0);
  EXPECT_FALSE(ringOrientation(view, cam, {-1200, -3600, 140}, 0).has_value());
  EXPECT_FALSE(ringOrientation(FrameView{}, cam, {-1200, 0, 140}, 0).has_value());
}

}  // namespace
}  // namespace dv
