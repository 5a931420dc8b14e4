// Pixel pipeline on the synthetic renderer's scenes (uneven light, dark and
// noisy, blue white balance, gray carpet): a small camera over part of each
// preset keeps the test fast while the field resolution stays that of the
// 2448x2048 preset camera.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "geometry/robot_pattern.h"
#include "pipeline/cpu_pipeline.h"
#include "synth/renderer.h"
#include "synth/scene.h"

namespace dv {
namespace {

struct SceneResult {
  std::vector<double> center_errors, side_errors, ball_errors;
  int missed = 0;
};

SceneResult runScene(const std::string& name) {
  SceneSpec spec = loadScene(std::string(DV_SOURCE_DIR) + "/config/scenes/" + name + ".yaml");
  // 768x640 px straight down over the first robot, at the preset's height
  // and focal length (same millimetres per pixel).
  const auto& big = spec.cameras.at(0).calib;
  const CameraModel big_model(big);
  const FieldMm target = spec.robots.empty() ? FieldMm{0, 0} : spec.robots[0].position;
  const double height = big_model.position().z();
  spec.cameras = {makeCamera(0, {target.x + 40, target.y - 30, height}, {target.x + 40, target.y - 30, 0},
                             big.focal_length, big.distortion, {0, 0}, 768, 640)};
  spec.frames = 1;
  Renderer renderer(spec);
  const auto frame = renderer.render(0, 0);
  const CameraModel cam(spec.cameras[0].calib);
  PipelineOptions opt;
  opt.bayer = spec.bayer ? BayerPattern::RGGB : BayerPattern::None;
  CpuPipeline pipe(cam, spec.field, opt);
  BlobList blobs;
  EXPECT_TRUE(pipe.process(frame.image, blobs)) << pipe.lastError();

  SceneResult res;
  // Blob positions are on the rectification plane; compare at the object's
  // own height by moving along the camera ray.
  auto nearest = [&](double x, double y, double h) {
    double best = 1e9;
    for (const auto& b : blobs.blobs) {
      const auto px = pipe.gridToImage(b.grid);
      if (!px) continue;
      const auto p = cam.imageToField(*px, h);
      if (p) best = std::min(best, std::hypot(p->x - x, p->y - y));
    }
    return best;
  };
  auto inner = [&](double u, double v) { return u > 120 && v > 120 && u < 768 - 120 && v < 640 - 120; };
  for (const auto* list : {&frame.truth.robots_yellow(), &frame.truth.robots_blue()}) {
    for (const auto& r : *list) {
      if (!inner(r.pixel_x(), r.pixel_y())) continue;
      const double e = nearest(r.x(), r.y(), r.height());
      if (e > 5) ++res.missed;
      else res.center_errors.push_back(e);
      for (const auto& o : RobotPatternGeometry::kSideBlobs) {
        const double c = std::cos(r.orientation()), s = std::sin(r.orientation());
        const double es = nearest(r.x() + c * o.x - s * o.y, r.y() + s * o.x + c * o.y, r.height());
        if (es > 8) ++res.missed;
        else res.side_errors.push_back(es);
      }
    }
  }
  for (const auto& b : frame.truth.balls()) {
    if (!inner(b.pixel_x(), b.pixel_y())) continue;
    const double e = nearest(b.x(), b.y(), b.z());
    if (e > 8) ++res.missed;
    else res.ball_errors.push_back(e);
  }
  return res;
}

double median(std::vector<double> v) {
  if (v.empty()) return 0;
  std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
  return v[v.size() / 2];
}

class PipelineScene : public ::testing::TestWithParam<std::string> {};

TEST_P(PipelineScene, EveryBlobFoundCenterBlobsSubMillimetre) {
  const auto res = runScene(GetParam());
  ASSERT_FALSE(res.center_errors.empty()) << "no robot in view";
  EXPECT_EQ(res.missed, 0);
  EXPECT_LT(median(res.center_errors), 1.2);
  // Side blobs share their window with the robot's edge and neighbours:
  // a few millimetres (the full preset frames give medians of 0.5..1.3 mm).
  EXPECT_LT(median(res.side_errors), 4.0);
  for (double e : res.ball_errors) EXPECT_LT(e, 3.0);
}

INSTANTIATE_TEST_SUITE_P(Presets, PipelineScene,
                         ::testing::Values("top_down_div_b_half", "uneven_light", "dark_noisy",
                                           "blue_white_balance", "gray_carpet"));

}  // namespace
}  // namespace dv
