// Full Bayer sampling (a co-sited sample per pixel) and the automatic choice
// between it and 2x2 subsampling.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "pipeline/bayer_full.h"
#include "pipeline/bayer_sampling.h"
#include "pipeline/bayer_subsample.h"
#include "pipeline/cpu_pipeline.h"
#include "pipeline/kernels.h"
#include "pipeline_test_scene.h"
#include "synth/scene.h"

namespace dv {
namespace {

constexpr BayerPattern kPatterns[] = {BayerPattern::RGGB, BayerPattern::GRBG, BayerPattern::GBRG,
                                      BayerPattern::BGGR};

cv::Mat randomMosaic(int w, int h, unsigned seed) {
  cv::Mat raw(h, w, CV_8UC1);
  std::mt19937 rng(seed);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) raw.at<uint8_t>(y, x) = static_cast<uint8_t>(rng() & 255);
  return raw;
}

ChromaFixed drgbFixed() {
  const ChromaTransform t = ChromaTransform::of(ColorSpace::DRGB);
  ChromaFixed k{};
  for (int c = 0; c < 3; ++c)
    k.a[c] = static_cast<int>(std::lround(t.a[c] * 1024)), k.b[c] = static_cast<int>(std::lround(t.b[c] * 1024));
  return k;
}

TEST(BayerFull, EveryPixelCoSitesChannelsAtTheWindowCenter) {
  // Linear ramps: interpolation is exact, so sample (x, y) must equal the
  // ramps at (x + 0.5, y + 0.5) for every pixel parity and every pattern.
  const int w = 16, h = 12;
  auto red = [](double u, double v) { return 20 + 6 * u + 2 * v; };
  auto green = [](double u, double v) { return 200 - 3 * u + 4 * v; };
  auto blue = [](double u, double v) { return 40 + 1 * u + 9 * v; };
  for (auto pattern : kPatterns) {
    const auto s = bayerSites(pattern);
    cv::Mat raw(h, w, CV_8UC1);
    for (int v = 0; v < h; ++v)
      for (int u = 0; u < w; ++u) {
        double val = green(u, v);
        if ((u & 1) == s.rx && (v & 1) == s.ry) val = red(u, v);
        if ((u & 1) == s.bx && (v & 1) == s.by) val = blue(u, v);
        raw.at<uint8_t>(v, u) = cv::saturate_cast<uint8_t>(val);
      }
    // Interior windows (their neighbours of each color lie in the image).
    for (int y = 1; y < h - 2; ++y)
      for (int x = 1; x < w - 2; ++x) {
        float rgb[3];
        fullBayerRgbAt(raw, pattern, x, y, rgb);
        const double u = x + 0.5, v = y + 0.5;
        EXPECT_NEAR(rgb[0], red(u, v), 1.0) << bayerPatternName(pattern) << " R at " << x << "," << y;
        EXPECT_NEAR(rgb[1], green(u, v), 1.0) << bayerPatternName(pattern) << " G at " << x << "," << y;
        EXPECT_NEAR(rgb[2], blue(u, v), 1.0) << bayerPatternName(pattern) << " B at " << x << "," << y;
      }
  }
}

TEST(BayerFull, EvenPixelsAreTheSubsampledCellsBordersIncluded) {
  const int w = 40, h = 22;
  const cv::Mat raw = randomMosaic(w, h, 7);
  const ChromaFixed k = drgbFixed();
  for (auto pattern : kPatterns) {
    std::vector<uint32_t> full(static_cast<size_t>(w) * h), sub(static_cast<size_t>(w / 2) * (h / 2));
    fullBayerChromaRows(raw, pattern, k, full.data(), 0, h, 0, w);
    bayerChromaRows(raw, pattern, k, sub.data(), 0, h / 2, 0, w / 2);
    long diff = 0;
    for (int j = 0; j < h / 2; ++j)
      for (int i = 0; i < w / 2; ++i)
        diff += full[static_cast<size_t>(2 * j) * w + 2 * i] != sub[static_cast<size_t>(j) * (w / 2) + i];
    EXPECT_EQ(diff, 0) << bayerPatternName(pattern);
  }
}

TEST(BayerFull, ChromaRowsAgreeWithTheSampleColorForAnyColumnRange) {
  // The vectorised interior and the border path against the one-sample
  // function (which the blob colors and the OpenCL kernel follow).
  const int w = 38, h = 14;
  const cv::Mat raw = randomMosaic(w, h, 11);
  const ChromaFixed k = drgbFixed();
  for (auto pattern : kPatterns) {
    for (const auto& cols : {std::pair{0, w}, std::pair{3, 31}, std::pair{1, 2}, std::pair{6, 7}}) {
      std::vector<uint32_t> full(static_cast<size_t>(w) * h, 0xdeadbeefu);
      fullBayerChromaRows(raw, pattern, k, full.data(), 0, h, cols.first, cols.second);
      long diff = 0, touched = 0;
      for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
          const uint32_t got = full[static_cast<size_t>(y) * w + x];
          if (x < cols.first || x >= cols.second) {
            touched += got != 0xdeadbeefu;
            continue;
          }
          float rgb[3];
          fullBayerRgbAt(raw, pattern, x, y, rgb);
          diff += got != packChroma(k, static_cast<int>(rgb[0]), static_cast<int>(rgb[1]), static_cast<int>(rgb[2]));
        }
      EXPECT_EQ(diff, 0) << bayerPatternName(pattern) << " columns " << cols.first << ".." << cols.second;
      EXPECT_EQ(touched, 0) << "wrote outside the column range";
    }
  }
}

// The preset's top-down camera, optionally at half the resolution (same
// pose, half the focal length).
CameraModel presetCamera(const char* preset, bool half) {
  CameraCalibration c = presetScene(preset).cameras.at(0).calib;
  if (half) {
    c.focal_length /= 2;
    c.principal_point_x = (c.principal_point_x + 0.5) / 2 - 0.5;
    c.principal_point_y = (c.principal_point_y + 0.5) / 2 - 0.5;
    c.image_width /= 2;
    c.image_height /= 2;
  }
  return CameraModel(c);
}

TEST(BayerSamplingChoice, FollowsTheFieldFootprintOfA2x2Cell) {
  const FieldModel field = FieldModel::divisionB();
  PipelineOptions opt;
  // 5 m over the field: 5.6 mm per cell at 2448 x 2048, 11 mm at 1224 x 1024.
  const auto fine = chooseBayerSampling(presetCamera("top_down_div_b_half", false), field, opt);
  EXPECT_EQ(fine.mode, BayerSampling::Subsample) << fine.describe();
  EXPECT_TRUE(fine.automatic);
  EXPECT_NEAR(fine.median_cell_mm, 5.6, 0.3);
  EXPECT_LT(fine.coarse_fraction, 0.01);
  const auto coarse = chooseBayerSampling(presetCamera("top_down_div_b_half", true), field, opt);
  EXPECT_EQ(coarse.mode, BayerSampling::Full) << coarse.describe();
  EXPECT_NEAR(coarse.median_cell_mm, 11.2, 0.5);
  EXPECT_GT(coarse.coarse_fraction, 0.99);
  // 1.6 m high at the touch line: near cells are fine, far ones stretched
  // along the viewing direction.
  const auto side = chooseBayerSampling(presetCamera("side_view", false), field, opt);
  EXPECT_EQ(side.mode, BayerSampling::Full) << side.describe();
  EXPECT_GT(side.coarse_fraction, 0.5);
  EXPECT_LT(side.coarse_fraction, 1.0);
  EXPECT_NE(side.describe().find("full (auto"), std::string::npos) << side.describe();

  // Requests are kept; RGB input has nothing to choose.
  opt.bayer_sampling = BayerSampling::Subsample;
  const auto forced = chooseBayerSampling(presetCamera("top_down_div_b_half", true), field, opt);
  EXPECT_EQ(forced.mode, BayerSampling::Subsample);
  EXPECT_FALSE(forced.automatic);
  EXPECT_NE(forced.describe().find("requested"), std::string::npos) << forced.describe();
  opt.bayer = BayerPattern::None;
  EXPECT_TRUE(chooseBayerSampling(presetCamera("top_down_div_b_half", true), field, opt).rgb);
}

TEST(BayerSamplingChoice, ParsesNames) {
  BayerSampling s = BayerSampling::Auto;
  ASSERT_TRUE(parseBayerSampling("FULL", s));
  EXPECT_EQ(s, BayerSampling::Full);
  ASSERT_TRUE(parseBayerSampling("subsample", s));
  EXPECT_EQ(s, BayerSampling::Subsample);
  ASSERT_TRUE(parseBayerSampling("auto", s));
  EXPECT_EQ(s, BayerSampling::Auto);
  EXPECT_FALSE(parseBayerSampling("half", s));
  EXPECT_STREQ(bayerSamplingName(BayerSampling::Full), "full");
}

// A coarse camera (5 mm per pixel, 10 mm per 2x2 cell) in the CPU pipeline:
// auto picks full sampling and the grid follows the pixels; every disc is
// found once, within a fraction of a cell. (Painted discs have sharp,
// unblurred edges, where green at the pixel pitch and red/blue on their
// 2-pixel lattice disagree most: median 1.3 mm, one disc 6.5 mm off, against
// 0.9 and 2.4 mm with subsampling. On rendered scenes, which have lens blur,
// full sampling is the more precise one; see detection_scene_test.cpp.)
TEST(BayerFull, CoarseCameraFindsDiscsWithFullSampling) {
  const auto cam = test::topDownCamera(1000, 500, 150 + 5000, 1000, 640, 480);
  const FieldModel field = FieldModel::divisionB();
  test::PaintedScene scene;
  const test::Color colors[4] = {test::kPink, test::kGreen, test::kYellow, test::kBlue};
  for (int i = 0; i < 8; ++i) {
    const FieldMm c{420.3 + 150.7 * i, 250.6 + 83.1 * i + (i % 2) * 251.4};
    scene.discs.push_back({c, 70, test::kBlack});
    scene.discs.push_back({c, i % 4 < 2 ? 20.0 : 25.0, colors[i % 4]});
  }
  const cv::Mat raw = scene.render(cam, BayerPattern::RGGB);
  CpuPipeline pipe(cam, field, PipelineOptions{});
  EXPECT_EQ(pipe.options().bayer_sampling, BayerSampling::Full) << pipe.samplingNote();
  EXPECT_NE(pipe.samplingNote().find("full (auto"), std::string::npos) << pipe.samplingNote();
  EXPECT_NEAR(pipe.grid().scale, 5.0, 0.1);  // the pixels' own spacing
  BlobList blobs;
  ASSERT_TRUE(pipe.process(raw, blobs)) << pipe.lastError();
  std::vector<double> errors;
  for (const auto& d : scene.discs) {
    if (d.radius > 30) continue;
    int hits = 0;
    double best = 1e9;
    for (const auto& b : blobs.blobs) {
      const double e = std::hypot(b.position.x - d.center.x, b.position.y - d.center.y);
      best = std::min(best, e);
      hits += e < 10;
    }
    EXPECT_EQ(hits, 1) << "disc at " << d.center.x << "," << d.center.y;
    errors.push_back(best);
  }
  std::nth_element(errors.begin(), errors.begin() + errors.size() / 2, errors.end());
  EXPECT_LT(errors[errors.size() / 2], 2.0);
  EXPECT_EQ(blobs.blobs.size(), errors.size());

  // Subsampling on request: the 5.6 mm grid of coarse cameras.
  PipelineOptions sub;
  sub.bayer_sampling = BayerSampling::Subsample;
  CpuPipeline coarse(cam, field, sub);
  EXPECT_EQ(coarse.options().bayer_sampling, BayerSampling::Subsample);
  EXPECT_NEAR(coarse.grid().scale, kLowResolutionGridMm, 1e-9);
}

}  // namespace
}  // namespace dv
