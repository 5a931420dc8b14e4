// The coarse search (PipelineOptions::coarse_search): the binned mosaic, and
// blobs found on the coarse grid but placed and scored on the full one, so
// that they are where the full search puts them.
#include <gtest/gtest.h>

#include <cmath>
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

// A 768x640 camera straight down over the first robot of a preset, at the
// preset camera's millimetres per pixel (a 5.6 mm grid: the coarse search runs).
struct PresetFrame {
  CameraModel cam{CameraCalibration{}};
  FieldModel field;
  cv::Mat image;
};

PresetFrame presetFrame(const std::string& name) {
  SceneSpec spec = loadScene(std::string(DV_SOURCE_DIR) + "/config/scenes/" + name + ".yaml");
  const auto& big = spec.cameras.at(0).calib;
  const double height = CameraModel(big).position().z();
  const FieldMm t = spec.robots.at(0).position;
  spec.cameras = {makeCamera(0, {t.x + 60, t.y - 40, height}, {t.x + 60, t.y - 40, 0}, big.focal_length,
                             big.distortion, {0, 0}, 768, 640)};
  spec.frames = 1;
  Renderer renderer(spec);
  return {CameraModel(spec.cameras[0].calib), spec.field, renderer.render(0, 0).image};
}

class CoarseSearch : public ::testing::TestWithParam<std::string> {};

TEST_P(CoarseSearch, FindsTheFullSearchsBlobsAtTheirPlaces) {
  const PresetFrame f = presetFrame(GetParam());
  PipelineOptions full_opt;
  full_opt.coarse_search = false;
  CpuPipeline coarse(f.cam, f.field, {}), full(f.cam, f.field, full_opt);
  ASSERT_NE(coarse.samplingNote().find("coarse search"), std::string::npos) << coarse.samplingNote();
  ASSERT_EQ(full.samplingNote().find("coarse search"), std::string::npos) << full.samplingNote();
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
      if (match) EXPECT_NEAR(match->score, x.score, 0.02 * x.score);
    }
  };
  expectIn(b, a, "full-search");
  expectIn(a, b, "coarse-search");
}

INSTANTIATE_TEST_SUITE_P(Presets, CoarseSearch,
                         ::testing::Values("top_down_div_b_half", "dark_noisy", "uneven_light", "gray_carpet"));

}  // namespace
}  // namespace dv
