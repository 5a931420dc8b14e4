// The coarse search (PipelineOptions::coarse_search): the binned mosaic, and
// blobs found on the coarse grid but placed and scored on the full one, so
// that they are where the full search puts them.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <random>
#include <string>

#include "pipeline/cpu_pipeline.h"
#include "pipeline/mosaic_binning.h"
#include "synth/renderer.h"
#include "synth/scene.h"

namespace dv {
namespace {

TEST(MosaicBinning, EachSiteIsTheMeanOfItsFourPixelsInTheBlock) {
  // 72 columns: the vector path's blocks and the scalar tail both run.
  const int w = 72, h = 24;
  cv::Mat raw(h, w, CV_8UC1);
  std::mt19937 rng(7);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) raw.at<uint8_t>(y, x) = static_cast<uint8_t>(rng() & 255);
  cv::Mat out(h / 2, w / 2, CV_8UC1, cv::Scalar(0));
  binMosaicRows(raw, out, 0, h / 4);
  for (int y = 0; y < h / 2; ++y)
    for (int x = 0; x < w / 2; ++x) {
      // Output pixel (x, y): site (x & 1, y & 1) of block (x / 2, y / 2).
      const int bx = 4 * (x / 2) + (x & 1), by = 4 * (y / 2) + (y & 1);
      const double mean = (raw.at<uint8_t>(by, bx) + raw.at<uint8_t>(by, bx + 2) + raw.at<uint8_t>(by + 2, bx) +
                           raw.at<uint8_t>(by + 2, bx + 2)) /
                          4.0;
      // Two rounded halvings: at most a level off.
      EXPECT_NEAR(out.at<uint8_t>(y, x), mean, 1.0) << x << "," << y;
    }
}

// A 768x640 camera over the first robot of a preset (after `change`), at the
// preset camera's millimetres per pixel (a 5.6 mm grid: the coarse search
// runs): straight down, or from the preset camera's place (its parallax);
// or the preset's own camera (`whole`).
struct PresetFrame {
  CameraModel cam{CameraCalibration{}};
  FieldModel field;
  cv::Mat image;
};

PresetFrame presetFrame(const std::string& name, const std::function<void(SceneSpec&)>& change = {},
                        bool overhead = true, bool whole = false) {
  SceneSpec spec = loadScene(std::string(DV_SOURCE_DIR) + "/config/scenes/" + name + ".yaml");
  if (change) change(spec);
  spec.frames = 1;
  if (whole) {
    spec.cameras.resize(1);
    return {CameraModel(spec.cameras[0].calib), spec.field, Renderer(spec).render(0, 0).image};
  }
  const auto& big = spec.cameras.at(0).calib;
  const Eigen::Vector3d c = CameraModel(big).position();
  const FieldMm t = spec.robots.at(0).position;
  const Eigen::Vector3d from = overhead ? Eigen::Vector3d(t.x + 60, t.y - 40, c.z()) : c;
  const Eigen::Vector3d to = overhead ? Eigen::Vector3d(t.x + 60, t.y - 40, 0) : Eigen::Vector3d(t.x, t.y, 0);
  spec.cameras = {makeCamera(0, {from.x(), from.y(), from.z()}, {to.x(), to.y(), to.z()}, big.focal_length,
                             big.distortion, {0, 0}, 768, 640)};
  spec.frames = 1;
  Renderer renderer(spec);
  return {CameraModel(spec.cameras[0].calib), spec.field, renderer.render(0, 0).image};
}

class CoarseSearch : public ::testing::TestWithParam<std::string> {};

TEST_P(CoarseSearch, FindsTheFullSearchsBlobsAtTheirPlaces) {
  // The side view from its stand: a sample per pixel and, far off, a
  // whitened gradient.
  const bool side = GetParam() == "side_view";
  const PresetFrame f = presetFrame(GetParam(), {}, /*overhead=*/true, /*whole=*/side);
  PipelineOptions full_opt;
  full_opt.coarse_search = false;
  CpuPipeline coarse(f.cam, f.field, {}), full(f.cam, f.field, full_opt);
  ASSERT_NE(coarse.samplingNote().find("coarse search"), std::string::npos) << coarse.samplingNote();
  ASSERT_EQ(full.samplingNote().find("coarse search"), std::string::npos) << full.samplingNote();
  if (side) {
    ASSERT_NE(coarse.samplingNote().find("sampling full"), std::string::npos) << coarse.samplingNote();
  }
  BlobList a, b;
  ASSERT_TRUE(coarse.process(f.image, a)) << coarse.lastError();
  ASSERT_TRUE(full.process(f.image, b)) << full.lastError();
  ASSERT_GE(b.blobs.size(), 5u);
  const double threshold = PipelineOptions{}.threshold;
  // Each clear blob of one search is in the other, at the same place (the
  // same full-grid scores; only the exposure gain differs a little). Peaks
  // just above the threshold on a noisy carpet may score below the coarse
  // pass's lowered threshold there.
  auto expectIn = [&](const BlobList& from, const BlobList& in, const char* what) {
    for (const Blob& x : from.blobs) {
      if (x.streak || x.score < 1.5 * threshold) continue;
      double best = 1e9;
      const Blob* match = nullptr;
      for (const Blob& y : in.blobs) {
        const double d = std::hypot(x.position.x - y.position.x, x.position.y - y.position.y);
        if (d < best) best = d, match = &y;
      }
      EXPECT_LT(best, 0.05) << what << " blob at " << x.position.x << "," << x.position.y;
      if (match) {
        EXPECT_NEAR(match->score, x.score, 0.02 * x.score);
      }
    }
  };
  expectIn(b, a, "full-search");
  expectIn(a, b, "coarse-search");
}

// Fast-ball candidates (streak_score.h) near the ball are the full search's:
// the same lattice peaks, placed the same. A ball pressed against a robot
// is found by this pass only, 30-40 mm from a side blob, where a candidate
// placed a few millimetres off is taken for that blob.
TEST(CoarseSearch, FindsTheFullSearchsFastBallsNearTheBall) {
  struct Placement {
    double orientation, bearing, distance, speed;  // rad, rad, mm, mm/s
  };
  const Placement placements[] = {{-1.0, 0.0, 77.5, 0},   {-0.1, 1.4, 107.5, 0}, {0.8, 0.0, 77.5, 0},
                                  {1.7, 1.4, 107.5, 0},   {0.3, 2.2, 300, 6500}, {2.0, -0.7, 250, 5000}};
  int streak_balls = 0;
  for (const Placement& pl : placements) {
    FieldMm ball;
    const PresetFrame f = presetFrame("top_down_div_b_half", [&](SceneSpec& s) {
      SceneRobot r = s.robots.at(0);
      r.position = {-2400, 500};  // far off the camera's axis: the body hides part of the ball
      s.robots = {r};
      s.robots[0].orientation = pl.orientation;
      const double a = pl.orientation + pl.bearing;
      ball = {r.position.x + pl.distance * std::cos(a), r.position.y + pl.distance * std::sin(a)};
      s.ball.present = true;
      s.ball.position = {ball.x, ball.y, 21.5};
      s.ball.velocity = {pl.speed * std::cos(a), pl.speed * std::sin(a), 0};
      s.ball.kicks.clear();
      s.motion_blur = pl.speed > 0;
      s.lighting.exposure_time = 0.008;
    }, /*overhead=*/false);
    PipelineOptions full_opt;
    full_opt.coarse_search = false;
    CpuPipeline coarse(f.cam, f.field, {}), full(f.cam, f.field, full_opt);
    BlobList a, b;
    ASSERT_TRUE(coarse.process(f.image, a)) << coarse.lastError();
    ASSERT_TRUE(full.process(f.image, b)) << full.lastError();
    auto nearBall = [&](const BlobList& list) {
      std::vector<FieldMm> out;
      for (const Blob& x : list.blobs)
        if (x.streak && std::hypot(x.position.x - ball.x, x.position.y - ball.y) < 60) out.push_back(x.position);
      return out;
    };
    const std::vector<FieldMm> in_coarse = nearBall(a), in_full = nearBall(b);
    ASSERT_EQ(in_coarse.size(), in_full.size()) << "ball at " << ball.x << "," << ball.y;
    for (size_t i = 0; i < in_full.size(); ++i)
      EXPECT_LT(std::hypot(in_coarse[i].x - in_full[i].x, in_coarse[i].y - in_full[i].y), 0.05)
          << "ball at " << ball.x << "," << ball.y;
    streak_balls += static_cast<int>(in_full.size());
  }
  // The placements exercise the pass: the ball at the side and the fastest
  // ball are found by it.
  EXPECT_GE(streak_balls, 2);
}

INSTANTIATE_TEST_SUITE_P(Presets, CoarseSearch,
                         ::testing::Values("top_down_div_b_half", "dark_noisy", "uneven_light", "gray_carpet",
                                           "side_view"));

}  // namespace
}  // namespace dv
