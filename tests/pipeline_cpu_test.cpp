// CPU pixel pipeline: Bayer subsampling, rectification extent, blob finding
// accuracy and the normalised threshold on painted scenes.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "core/error.h"
#include "pipeline/bayer_subsample.h"
#include "pipeline/cpu_pipeline.h"
#include "pipeline/score_windows.h"
#include "synth/scene.h"
#include "pipeline_test_scene.h"

namespace dv {
namespace {

using test::addRobot;
using test::PaintedScene;
using test::topDownCamera;

// 2 mm per full pixel at the plane: ~4 mm per grid cell after subsampling.
CameraModel smallTopDown(BayerPattern bayer = BayerPattern::RGGB) {
  const bool rgb = bayer == BayerPattern::None;
  // RGB images sample every pixel, so use a coarser image for the same cell size.
  return rgb ? topDownCamera(1000, 500, 150 + 4000, 1000, 320, 240)
             : topDownCamera(1000, 500, 150 + 2000, 1000, 640, 480);
}

PaintedScene robotScene() {
  PaintedScene s;
  const test::Color sides[4] = {test::kPink, test::kGreen, test::kGreen, test::kPink};
  addRobot(s, {820.3, 610.7}, 0.4, test::kYellow, sides);
  addRobot(s, {1170.9, 380.2}, -2.1, test::kBlue, sides);
  s.discs.push_back({{1150.4, 700.6}, 21.5, test::kOrange});
  return s;
}

// Isolated discs of every blob color and size on the carpet.
PaintedScene discScene() {
  PaintedScene s;
  const test::Color colors[6] = {test::kOrange, test::kYellow, test::kBlue,
                                 test::kPink, test::kGreen, test::kOrange};
  const double radii[6] = {21.5, 25, 25, 20, 20, 21.5};
  for (int i = 0; i < 6; ++i) {
    const FieldMm c{520.3 + 170.7 * i, 300.6 + 61.3 * i + (i % 2) * 330.2};
    // Pattern colors sit on a dark robot top, the ball on the carpet.
    if (i != 0 && i != 5) s.discs.push_back({c, 70, test::kBlack});
    s.discs.push_back({c, radii[i], colors[i]});
  }
  return s;
}

// Each disc with radius in [min_r, max_r] must be matched by exactly one blob
// within `tolerance` mm; returns the largest error over those discs and
// counts blobs that match no disc at all (within 10 mm of any disc).
double matchDiscs(const PaintedScene& s, const BlobList& blobs, double min_r, double max_r,
                  double tolerance, int* stray_blobs = nullptr) {
  double worst = 0;
  for (const auto& d : s.discs) {
    if (d.radius < min_r || d.radius > max_r) continue;
    int hits = 0;
    double best = 1e9;
    for (const auto& b : blobs.blobs) {
      const double e = std::hypot(b.position.x - d.center.x, b.position.y - d.center.y);
      best = std::min(best, e);
      hits += e < tolerance;
    }
    EXPECT_EQ(hits, 1) << "disc r=" << d.radius << " at " << d.center.x << "," << d.center.y
                       << ": nearest blob " << best << " mm";
    worst = std::max(worst, best);
    if (getenv("DV_PIPELINE_TEST_VERBOSE"))
      printf("disc r=%.1f at %.1f,%.1f error %.3f mm\n", d.radius, d.center.x, d.center.y, best);
  }
  if (stray_blobs) {
    *stray_blobs = 0;
    for (const auto& b : blobs.blobs) {
      double best = 1e9;
      for (const auto& d : s.discs)
        if (d.radius <= 30)
          best = std::min(best, std::hypot(b.position.x - d.center.x, b.position.y - d.center.y));
      *stray_blobs += best > 10;
    }
  }
  return worst;
}

TEST(PipelineBayer, EveryPatternCoSitesChannelsAtTheCellCenter) {
  // Channels are linear ramps, so interpolation to the cell center is exact:
  // the co-sited value of cell (i, j) must equal the ramp at (2i+.5, 2j+.5).
  const int w = 16, h = 12;
  auto red = [](double u, double v) { return 20 + 6 * u + 2 * v; };
  auto green = [](double u, double v) { return 200 - 3 * u + 4 * v; };
  auto blue = [](double u, double v) { return 40 + 1 * u + 9 * v; };
  for (auto pattern : {BayerPattern::RGGB, BayerPattern::GRBG, BayerPattern::GBRG, BayerPattern::BGGR}) {
    const auto sites = bayerSites(pattern);
    cv::Mat raw(h, w, CV_8UC1);
    for (int v = 0; v < h; ++v)
      for (int u = 0; u < w; ++u) {
        const int cx = u & 1, cy = v & 1;
        double val = green(u, v);
        if (cx == sites.rx && cy == sites.ry) val = red(u, v);
        if (cx == sites.bx && cy == sites.by) val = blue(u, v);
        raw.at<uint8_t>(v, u) = cv::saturate_cast<uint8_t>(val);
      }
    std::vector<uint8_t> rgbx(4 * (w / 2) * (h / 2));
    subsampleBayerRows(raw, pattern, rgbx.data(), 0, h / 2);
    // Interior cells only: at the border the neighbour is repeated.
    for (int j = 1; j < h / 2 - 1; ++j)
      for (int i = 1; i < w / 2 - 1; ++i) {
        const uint8_t* p = &rgbx[4 * (j * (w / 2) + i)];
        const double u = 2 * i + 0.5, v = 2 * j + 0.5;
        EXPECT_NEAR(p[0], red(u, v), 1.0) << bayerPatternName(pattern) << " R at " << i << "," << j;
        EXPECT_NEAR(p[1], green(u, v), 1.0) << bayerPatternName(pattern) << " G at " << i << "," << j;
        EXPECT_NEAR(p[2], blue(u, v), 1.0) << bayerPatternName(pattern) << " B at " << i << "," << j;
      }
  }
}

TEST(PipelineBayer, ParsesPatternNames) {
  BayerPattern p;
  ASSERT_TRUE(parseBayerPattern("GBRG", p));
  EXPECT_EQ(p, BayerPattern::GBRG);
  EXPECT_FALSE(parseBayerPattern("rgbg", p));
}

TEST(PipelineGrid, TopDownExtentAndScale) {
  const auto cam = smallTopDown();
  CpuPipeline pipe(cam, FieldModel::divisionB(), {});
  const auto& g = pipe.grid();
  // 640x480 px at 2 mm -> 1280 x 960 mm around (1000, 500); 4 mm per cell.
  EXPECT_NEAR(g.scale, 4.0, 0.01);
  const FieldMm a = g.toField({0, 0});
  const FieldMm b = g.toField({g.width - 1.0, g.height - 1.0});
  EXPECT_NEAR(a.x, 1000 - 640, 25);
  EXPECT_NEAR(a.y, 500 + 480, 25);
  EXPECT_NEAR(b.x, 1000 + 640, 25);
  EXPECT_NEAR(b.y, 500 - 480, 25);
  const GridPx back = g.toGrid(g.toField({12.25, 7.5}));
  EXPECT_NEAR(back.x, 12.25, 1e-9);
  EXPECT_NEAR(back.y, 7.5, 1e-9);
}

// An RGB frame carries no chroma finer than the Bayer mosaic it was made
// from, so its grid is the mosaic's: 2 px apart for a camera whose 2x2 cells
// serve (4 mm here, not the 2 mm of its pixels), a pixel apart for a camera
// whose cells are coarse (the side view's far field).
TEST(PipelineGrid, RgbFrameGetsItsMosaicsGrid) {
  const auto cam = smallTopDown();
  PipelineOptions rgb;
  rgb.bayer = BayerPattern::None;
  EXPECT_NEAR(checkedGrid(cam, FieldModel::divisionB(), rgb).scale, 4.0, 0.01);
  EXPECT_NEAR(checkedGrid(cam, FieldModel::divisionB(), {}).scale, 4.0, 0.01);
  const SceneSpec side = presetScene("side_view");
  const CameraModel side_cam(side.cameras[0].calib);
  PipelineOptions full;
  full.bayer_sampling = BayerSampling::Full;
  EXPECT_EQ(checkedGrid(side_cam, side.field, rgb).scale, checkedGrid(side_cam, side.field, full).scale);
  EXPECT_LT(checkedGrid(side_cam, side.field, rgb).scale, kLowResolutionGridMm);
}

TEST(PipelineBlobs, IsolatedDiscsAreFoundOnceWithSubMillimetreError) {
  const auto cam = smallTopDown();
  const auto scene = discScene();
  CpuPipeline pipe(cam, FieldModel::divisionB(), {});
  BlobList blobs;
  ASSERT_TRUE(pipe.process(scene.render(cam, BayerPattern::RGGB), blobs)) << pipe.lastError();
  int stray = 0;
  // Measured: 0.09..0.57 mm at 4 mm per cell (point-sampled Bayer sites, no
  // lens blur: the hardest case for the red and blue channels).
  EXPECT_LT(matchDiscs(scene, blobs, 0, 30, 5, &stray), 0.7);
  EXPECT_EQ(stray, 0);
  // The mean color is the disc's color.
  for (const auto& d : scene.discs)
    if (d.radius < 30)
      for (const auto& b : blobs.blobs)
      if (std::hypot(b.position.x - d.center.x, b.position.y - d.center.y) < 3) {
        EXPECT_NEAR(b.rgb[0], d.color.r, 20);
        EXPECT_NEAR(b.rgb[1], d.color.g, 20);
        EXPECT_NEAR(b.rgb[2], d.color.b, 20);
      }
}

TEST(PipelineBlobs, EveryRobotBlobAndTheBallFoundOnce) {
  const auto cam = smallTopDown();
  const auto scene = robotScene();
  CpuPipeline pipe(cam, FieldModel::divisionB(), {});
  BlobList blobs;
  ASSERT_TRUE(pipe.process(scene.render(cam, BayerPattern::RGGB), blobs)) << pipe.lastError();
  int stray = 0;
  // Center blobs and the ball: sub-millimetre.
  EXPECT_LT(matchDiscs(scene, blobs, 21, 30, 10, &stray), 0.7);
  EXPECT_EQ(stray, 0);
  // Side blobs sit 5 mm from the robot's edge, whose gradient shares their
  // window; they are found once, a few millimetres off at most.
  EXPECT_LT(matchDiscs(scene, blobs, 19, 20.5, 10), 8.0);
}

TEST(PipelineBlobs, SameBlobsAtThirtyPercentBrightness) {
  const auto cam = smallTopDown();
  auto scene = discScene();
  const auto robots = robotScene();
  scene.discs.insert(scene.discs.end(), robots.discs.begin(), robots.discs.end());
  CpuPipeline pipe(cam, FieldModel::divisionB(), {});
  BlobList bright, dark;
  ASSERT_TRUE(pipe.process(scene.render(cam, BayerPattern::RGGB), bright));
  scene.gain = 0.3;
  ASSERT_TRUE(pipe.process(scene.render(cam, BayerPattern::RGGB), dark));
  EXPECT_EQ(bright.blobs.size(), dark.blobs.size());
  int stray = 0;
  EXPECT_LT(matchDiscs(scene, dark, 0, 30, 10, &stray), 8.0);
  EXPECT_EQ(stray, 0);
  // Normalised scores barely move with exposure.
  for (const auto& b : bright.blobs)
    for (const auto& d : dark.blobs)
      if (std::hypot(b.position.x - d.position.x, b.position.y - d.position.y) < 1) {
        EXPECT_NEAR(d.score / b.score, 1.0, 0.25);
      }
}

TEST(PipelineBlobs, NoBlobsOnNoisyCarpet) {
  const auto cam = smallTopDown();
  PaintedScene s;
  s.noise_sigma = 4;
  s.supersample = 1;
  CpuPipeline pipe(cam, FieldModel::divisionB(), {});
  BlobList blobs;
  ASSERT_TRUE(pipe.process(s.render(cam, BayerPattern::RGGB), blobs));
  EXPECT_EQ(blobs.blobs.size(), 0u);
}

TEST(PipelineBlobs, NoBlobsOnWhiteLinesAndCrossings) {
  const auto cam = smallTopDown();
  PaintedScene s;
  s.noise_sigma = 2;
  s.supersample = 2;
  s.bands.push_back({{400, 500}, {1600, 500}, 10});   // along x
  s.bands.push_back({{1000, -100}, {1000, 1100}, 10});  // along y, crossing
  s.bands.push_back({{600, 200}, {600, 900}, 10});    // T junction with the first
  s.bands.push_back({{1300, 800}, {1500, 800}, 10});  // L corner with the next
  s.bands.push_back({{1500, 800}, {1500, 950}, 10});
  CpuPipeline pipe(cam, FieldModel::divisionB(), {});
  BlobList blobs;
  ASSERT_TRUE(pipe.process(s.render(cam, BayerPattern::RGGB), blobs));
  EXPECT_EQ(blobs.blobs.size(), 0u) << "first at " << (blobs.blobs.empty() ? 0 : blobs.blobs[0].position.x)
                                    << "," << (blobs.blobs.empty() ? 0 : blobs.blobs[0].position.y)
                                    << " score " << (blobs.blobs.empty() ? 0 : blobs.blobs[0].score);
}

TEST(PipelineBlobs, BgrInputCircleScoreAndYuvFindTheDiscs) {
  const auto scene = discScene();
  struct Case {
    BayerPattern bayer;
    BlobScoreKind score;
    ColorSpace color;
  };
  for (const auto& c : {Case{BayerPattern::None, BlobScoreKind::QuadrantMin, ColorSpace::DRGB},
                        Case{BayerPattern::RGGB, BlobScoreKind::CircleMin, ColorSpace::DRGB},
                        Case{BayerPattern::RGGB, BlobScoreKind::QuadrantMin, ColorSpace::YUV}}) {
    const auto cam = smallTopDown(c.bayer);
    PipelineOptions opt;
    opt.bayer = c.bayer;
    opt.score = c.score;
    opt.color = c.color;
    CpuPipeline pipe(cam, FieldModel::divisionB(), opt);
    BlobList blobs;
    ASSERT_TRUE(pipe.process(scene.render(cam, c.bayer), blobs)) << pipe.lastError();
    int stray = 0;
    EXPECT_LT(matchDiscs(scene, blobs, 0, 30, 5, &stray), 1.0);
    EXPECT_EQ(stray, 0);
  }
}

TEST(PipelineGrid, TiltedCameraSeeingTheHorizonIsClippedAndSafe) {
  // At the field edge, 1 m high, looking along +x slightly above horizontal.
  const double pitch = 0.05;  // rad above the horizon
  Eigen::Matrix3d look;      // rows: camera x, y, z axes in field coordinates
  const Eigen::Vector3d fwd(std::cos(pitch), 0, std::sin(pitch));
  const Eigen::Vector3d right(0, -1, 0);
  const Eigen::Vector3d down = fwd.cross(right);
  look.row(0) = right.transpose();
  look.row(1) = down.transpose();
  look.row(2) = fwd.transpose();
  auto calib = CameraCalibration::fromPose(0, 300, 159.5, 119.5, 0, look,
                                           Eigen::Vector3d(-4800, 0, 1000));
  calib.image_width = 320;
  calib.image_height = 240;
  const CameraModel cam(calib);
  const auto field = FieldModel::divisionB();
  CpuPipeline pipe(cam, field, {});
  const auto& g = pipe.grid();
  const auto area = field.withBoundary();
  const FieldMm a = g.toField({-0.5, -0.5}), b = g.toField({g.width - 0.5, g.height - 0.5});
  EXPECT_GE(a.x, area.x_min - 1e-6);
  EXPECT_LE(b.x, area.x_max + g.scale);
  EXPECT_LE(a.y, area.y_max + 1e-6);
  EXPECT_GE(b.y, area.y_min - g.scale);
  EXPECT_TRUE(std::isfinite(g.scale) && g.scale > 0);
  PaintedScene s;
  s.noise_sigma = 3;
  s.supersample = 1;
  s.discs.push_back({{-3500, 200}, 25, test::kOrange});
  BlobList blobs;
  ASSERT_TRUE(pipe.process(s.render(cam, BayerPattern::RGGB), blobs));
  for (const auto& bl : blobs.blobs) {
    EXPECT_TRUE(std::isfinite(bl.position.x) && std::isfinite(bl.position.y));
    EXPECT_TRUE(std::isfinite(bl.score));
  }
}

TEST(PipelineErrors, WrongFrameSizeAndTypeAreRejectedWithAMessage) {
  const auto cam = smallTopDown();
  CpuPipeline pipe(cam, FieldModel::divisionB(), {});
  BlobList blobs;
  blobs.blobs.resize(3);
  EXPECT_FALSE(pipe.process(cv::Mat(480, 642, CV_8UC1, cv::Scalar(0)), blobs));
  EXPECT_TRUE(blobs.blobs.empty());
  EXPECT_NE(pipe.lastError().find("642x480"), std::string::npos) << pipe.lastError();
  EXPECT_FALSE(pipe.process(cv::Mat(480, 640, CV_16UC1, cv::Scalar(0)), blobs));
  EXPECT_NE(pipe.lastError().find("8-bit"), std::string::npos) << pipe.lastError();
  EXPECT_FALSE(pipe.process(cv::Mat(), blobs));
  EXPECT_FALSE(pipe.lastError().empty());
  // A good frame afterwards still works.
  EXPECT_TRUE(pipe.process(cv::Mat(480, 640, CV_8UC1, cv::Scalar(60)), blobs)) << pipe.lastError();
}

TEST(PipelineErrors, CameraThatSeesNoFieldThrowsInputError) {
  // Far outside the field, looking down.
  const auto cam = topDownCamera(20000, 20000, 3000, 1000, 640, 480);
  EXPECT_THROW(CpuPipeline(cam, FieldModel::divisionB(), {}), InputError);
  auto calib = smallTopDown().calibration();
  calib.image_width = 0;
  EXPECT_THROW(CpuPipeline(CameraModel(calib), FieldModel::divisionB(), {}), InputError);
}

TEST(PipelineDebug, ViewsHaveTheGridSize) {
  const auto cam = smallTopDown();
  CpuPipeline pipe(cam, FieldModel::divisionB(), {});
  BlobList blobs;
  ASSERT_TRUE(pipe.process(robotScene().render(cam, BayerPattern::RGGB), blobs));
  for (const cv::Mat& m : {pipe.debugRectified(), pipe.debugGradient(), pipe.debugScore()}) {
    EXPECT_EQ(m.cols, pipe.grid().width);
    EXPECT_EQ(m.rows, pipe.grid().height);
    EXPECT_EQ(m.depth(), CV_8U);
  }
}

}  // namespace
}  // namespace dv

namespace dv {
namespace {

// Hysteresis on blobs: a faint disc (little chroma contrast to the carpet)
// 70 mm from a blob is a weak peak; the same faint disc far from every blob
// is nothing; neither is a blob.
TEST(PipelineBlobs, FaintDiscIsAWeakPeakOnlyNearABlob) {
  const auto cam = test::topDownCamera(1000, 500, 150 + 2000, 1000, 640, 480);
  PaintedScene s;
  const FieldMm ball{800.3, 500.6}, near{868.1, 524.9}, far{1400.2, 820.7};
  const test::Color faint{47, 119, 54};  // scores 0.18
  s.discs.push_back({ball, 21.5, test::kOrange});
  s.discs.push_back({near, 20, faint});
  s.discs.push_back({far, 20, faint});
  const cv::Mat raw = s.render(cam, BayerPattern::RGGB);
  for (bool weak_on : {true, false}) {
    PipelineOptions opt;
    if (!weak_on) opt.weak_threshold = 0;
    CpuPipeline pipe(cam, FieldModel::divisionB(), opt);
    BlobList blobs;
    ASSERT_TRUE(pipe.process(raw, blobs)) << pipe.lastError();
    ASSERT_EQ(blobs.blobs.size(), 1u);
    EXPECT_LT(std::hypot(blobs.blobs[0].position.x - ball.x, blobs.blobs[0].position.y - ball.y), 2);
    if (!weak_on) {
      EXPECT_TRUE(blobs.weak.empty());
      continue;
    }
    int near_hits = 0;
    for (const auto& w : blobs.weak) {
      EXPECT_GT(std::hypot(w.position.x - far.x, w.position.y - far.y), 50);
      if (std::hypot(w.position.x - near.x, w.position.y - near.y) < 3) {
        ++near_hits;
        EXPECT_GT(w.score, opt.weak_threshold);
        EXPECT_LE(w.score, opt.threshold);
      }
    }
    EXPECT_EQ(near_hits, 1);
  }
}

// Where the detector expects a fast ball, the same faint disc far from
// every blob is a weak peak, on the full grid and in the coarse search;
// the expectation holds until it is set again.
TEST(PipelineBlobs, FaintDiscIsAWeakPeakWhereAFastBallIsExpected) {
  const auto cam = test::topDownCamera(1000, 500, 150 + 2000, 1000, 640, 480);
  PaintedScene s;
  const FieldMm ball{800.3, 500.6}, far{1400.2, 820.7};
  s.discs.push_back({ball, 21.5, test::kOrange});
  s.discs.push_back({far, 20, {47, 119, 54}});  // scores 0.18
  const cv::Mat raw = s.render(cam, BayerPattern::RGGB);
  auto weakAtFar = [&](const BlobList& blobs) {
    int hits = 0;
    for (const auto& w : blobs.weak) hits += std::hypot(w.position.x - far.x, w.position.y - far.y) < 3;
    return hits;
  };
  for (bool coarse : {true, false}) {
    PipelineOptions opt;
    opt.coarse_search = coarse;
    CpuPipeline pipe(cam, FieldModel::divisionB(), opt);
    BlobList blobs;
    ExpectedPlaces expected;
    expected.at[expected.n++] = {far.x + 30, far.y - 20};  // a prediction is never exact
    pipe.expect(expected);
    ASSERT_TRUE(pipe.process(raw, blobs)) << pipe.lastError();
    ASSERT_EQ(blobs.blobs.size(), 1u);
    EXPECT_EQ(weakAtFar(blobs), 1) << (coarse ? "coarse search" : "full grid");
    ASSERT_TRUE(pipe.process(raw, blobs));
    EXPECT_EQ(weakAtFar(blobs), 1) << (coarse ? "coarse search" : "full grid") << ", the next frame";
    pipe.expect({});
    ASSERT_TRUE(pipe.process(raw, blobs));
    EXPECT_EQ(weakAtFar(blobs), 0) << (coarse ? "coarse search" : "full grid") << ", expectation withdrawn";
  }
}

}  // namespace
}  // namespace dv
