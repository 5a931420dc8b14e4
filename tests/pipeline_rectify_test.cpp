// Alternative paths of the CPU pipeline that must not change a bit: a camera
// turned by 90 degrees reads the chroma samples from a transposed copy; the
// quadrant score sums the table's columns band by band; with Bayer 2x2
// subsampling the pipeline goes from the mosaic to the score band by band.
#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "pipeline/bayer_subsample.h"
#include "pipeline/cpu_pipeline.h"
#include "pipeline/kernels.h"
#include "pipeline/remap_table.h"
#include "pipeline/score_windows.h"
#include "pipeline/thread_pool.h"
#include "pipeline_test_scene.h"

namespace dv {
namespace {

// 640x480 Bayer camera 2 m above the plane, image x along field y: grid rows
// (field x) run down image columns.
CameraModel turnedCamera() {
  Eigen::Matrix3d r;
  r << 0, 1, 0, 1, 0, 0, 0, 0, -1;
  auto calib = CameraCalibration::fromPose(0, 1000, 319.5, 239.5, 0, r, Eigen::Vector3d(1000, 500, 2150));
  calib.image_width = 640;
  calib.image_height = 480;
  return CameraModel(calib);
}

TEST(PipelineRectify, TransposedSamplesGiveBitIdenticalChroma) {
  const auto cam = turnedCamera();
  test::PaintedScene scene;
  const test::Color sides[4] = {test::kPink, test::kGreen, test::kGreen, test::kPink};
  test::addRobot(scene, {900.3, 560.7}, 0.7, test::kBlue, sides);
  scene.discs.push_back({{1150.4, 400.6}, 21.5, test::kOrange});
  scene.noise_sigma = 2;
  const cv::Mat raw = scene.render(cam, BayerPattern::GRBG);
  PipelineOptions opt;
  const RectifiedGrid grid = checkedGrid(cam, FieldModel::divisionB(), opt);
  ThreadPool pool(1);
  RemapTable table;
  table.build(cam, grid, opt.plane_height, SampleLattice{2, 0.5}, pool);
  ASSERT_TRUE(table.runsAlongColumns());
  const int stride = table.src_height + 16;
  const RemapTable table_t = table.transposed(stride);

  ChromaFixed k{};
  const auto t = ChromaTransform::of(ColorSpace::DRGB);
  for (int c = 0; c < 3; ++c) k.a[c] = static_cast<int>(std::lround(t.a[c] * 1024)), k.b[c] = static_cast<int>(std::lround(t.b[c] * 1024));
  const int ws = raw.cols / 2, hs = raw.rows / 2;
  std::vector<uint32_t> packed(static_cast<size_t>(ws) * hs, 0), packed_t(static_cast<size_t>(ws) * stride, 0);
  bayerChromaRows(raw, BayerPattern::GRBG, k, packed.data(), table.y_begin, table.y_end, table.x_begin, table.x_end);
  // In two row ranges, as the thread pool splits it (the second not a
  // multiple of the transposer's block).
  const int mid = table.y_begin + 37;
  bayerChromaRowsTransposed(raw, BayerPattern::GRBG, k, packed_t.data(), stride, table.y_begin, mid,
                            table.x_begin, table.x_end);
  bayerChromaRowsTransposed(raw, BayerPattern::GRBG, k, packed_t.data(), stride, mid, table.y_end,
                            table.x_begin, table.x_end);
  long moved = 0;
  for (int j = table.y_begin; j < table.y_end; ++j)
    for (int i = table.x_begin; i < table.x_end; ++i)
      moved += packed_t[static_cast<size_t>(i) * stride + j] != packed[static_cast<size_t>(j) * ws + i];
  EXPECT_EQ(moved, 0);

  const size_t cells = static_cast<size_t>(grid.width) * grid.height;
  std::vector<float> ca(cells), cb(cells), ca_t(cells), cb_t(cells);
  rectifyChromaRows(table, packed.data(), 0.01f, ca.data(), cb.data(), 0, grid.height);
  rectifyChromaRows(table_t, packed_t.data(), 0.01f, ca_t.data(), cb_t.data(), 0, grid.height);
  EXPECT_TRUE(ca == ca_t && cb == cb_t) << "integer interpolation must not depend on the sample order";
  float spread = 0;
  for (float v : ca) spread = std::max(spread, std::abs(v));
  EXPECT_GT(spread, 0.05f);  // the scene's colors reached the planes
}

TEST(PipelineRectify, TopDownCameraKeepsTheImageOrder) {
  const auto cam = test::topDownCamera(1000, 500, 150 + 2000, 1000, 640, 480);
  PipelineOptions opt;
  ThreadPool pool(1);
  RemapTable table;
  table.build(cam, checkedGrid(cam, FieldModel::divisionB(), opt), opt.plane_height, SampleLattice{2, 0.5}, pool);
  EXPECT_FALSE(table.runsAlongColumns());
}

TEST(PipelineScore, BandsMakingTheirOwnRowsGiveTheWholePlaneScore) {
  const int w = 157, h = 123, r = 5, q = 2;
  const double scale = 5.0 / 3;  // fractional: both gradient taps in use
  std::mt19937 rng(7);
  // Chroma steps large enough that the table wraps.
  std::uniform_real_distribution<float> c_dist(-30, 30);
  std::vector<float> ca(static_cast<size_t>(w) * h), cb(ca.size());
  for (auto& v : ca) v = c_dist(rng);
  for (auto& v : cb) v = c_dist(rng);
  std::vector<int32_t> g(ca.size());
  gradientDotRows(ca.data(), cb.data(), w, h, scale, g.data(), 0, h);
  std::vector<uint32_t> sat((w + 1ull) * (h + 1ull), 0);
  satRowPrefixRows(g.data(), w, h, sat.data(), 0, h);
  satColumnPrefix(sat.data(), w, h, 0, w + 1);
  std::vector<float> full(g.size(), -1), banded(g.size(), -1);
  quadrantMinScoreRows(sat.data(), w, h, r, q, full.data(), 0, h);
  std::vector<uint32_t> ring;
  const int bands[] = {0, 3, 40, 41, 90, h};  // every size, one inside the border
  for (int i = 0; i + 1 < 6; ++i)
    quadrantMinScoreFromChroma(ca.data(), cb.data(), w, h, scale, r, q, banded.data(), bands[i], bands[i + 1], ring);
  EXPECT_TRUE(full == banded);
  float top = 0;
  for (float v : full) top = std::max(top, v);
  EXPECT_GT(top, 0.0f);
}


// The whole-plane stages in turn, as the pipeline did before it went band by
// band: packed chroma, frame brightness, rectification, quadrant score.
std::vector<float> wholePlaneScore(const CameraModel& cam, const cv::Mat& raw, BayerPattern pattern,
                                   const CpuPipeline& cpu) {
  const PipelineOptions& opt = cpu.options();
  ThreadPool pool(1);
  RemapTable table;
  table.build(cam, cpu.grid(), opt.plane_height, SampleLattice{2, 0.5}, pool);
  ChromaFixed k{};
  const auto t = ChromaTransform::of(opt.color);
  for (int c = 0; c < 3; ++c) k.a[c] = static_cast<int>(std::lround(t.a[c] * 1024)), k.b[c] = static_cast<int>(std::lround(t.b[c] * 1024));
  const int ws = raw.cols / 2, hs = raw.rows / 2;
  std::vector<uint32_t> packed(static_cast<size_t>(ws) * hs, 0);
  bayerChromaRows(raw, pattern, k, packed.data(), table.y_begin, table.y_end, table.x_begin, table.x_end);
  uint64_t sum = 0, n = 0;
  const auto s = bayerSites(pattern);
  for (int y = table.y_begin; y < table.y_end; y += 16) {
    const uint8_t* r0 = raw.ptr<uint8_t>(2 * y);
    const uint8_t* r1 = raw.ptr<uint8_t>(2 * y + 1);
    for (int x = table.x_begin; x < table.x_end; x += 4) {
      const int all = r0[2 * x] + r0[2 * x + 1] + r1[2 * x] + r1[2 * x + 1];
      const int r = (s.ry ? r1 : r0)[2 * x + s.rx], b = (s.by ? r1 : r0)[2 * x + s.bx];
      sum += 2 * (r + b) + (all - r - b), n += 6;
    }
  }
  const float luma_mean = static_cast<float>(sum) / std::max<uint64_t>(1, n) + 1.0f;
  const int w = cpu.grid().width, h = cpu.grid().height;
  std::vector<float> ca(static_cast<size_t>(w) * h), cb(ca.size()), score(ca.size());
  rectifyChromaRows(table, packed.data(), 1.0f / (luma_mean * kPackedChromaScale), ca.data(), cb.data(), 0, h);
  std::vector<uint32_t> ring;
  const int q = scoreWindows(cpu.grid().scale, opt.score).inner_corner;
  quadrantMinScoreFromChroma(ca.data(), cb.data(), w, h, cpu.gradientScale(), cpu.quadrantRadius(), q,
                             score.data(), 0, h, ring);
  return score;
}

TEST(PipelineBands, MosaicToScoreBandByBandGivesTheWholePlaneScore) {
  test::PaintedScene scene;
  const test::Color sides[4] = {test::kPink, test::kGreen, test::kGreen, test::kPink};
  test::addRobot(scene, {900.3, 560.7}, 0.7, test::kBlue, sides);
  scene.discs.push_back({{1150.4, 400.6}, 21.5, test::kOrange});
  scene.noise_sigma = 2;
  struct Case {
    const char* what;
    CameraModel cam;
    BayerPattern pattern;
  };
  const Case cases[] = {{"turned camera (transposed samples)", turnedCamera(), BayerPattern::GRBG},
                        {"top-down camera", test::topDownCamera(1000, 500, 150 + 2000, 1000, 640, 480),
                         BayerPattern::BGGR}};
  for (const Case& c : cases) {
    const cv::Mat raw = scene.render(c.cam, c.pattern);
    PipelineOptions opt;
    opt.bayer = c.pattern;
    opt.bayer_sampling = BayerSampling::Subsample;
    opt.coarse_search = false;  // the full grid's score plane is compared
    std::vector<const float*> planes;
    std::vector<std::unique_ptr<CpuPipeline>> pipelines;
    std::vector<BlobList> blobs;
    for (int threads : {1, 3}) {  // 8 and 12 bands
      opt.threads = threads;
      pipelines.push_back(std::make_unique<CpuPipeline>(c.cam, FieldModel::divisionB(), opt));
      blobs.emplace_back();
      // Twice: the second frame runs on the buffers of the first.
      for (int frame = 0; frame < 2; ++frame) ASSERT_TRUE(pipelines.back()->process(raw, blobs.back()));
    }
    const CpuPipeline& cpu = *pipelines[0];
    const std::vector<float> want = wholePlaneScore(c.cam, raw, c.pattern, cpu);
    for (const auto& p : pipelines) {
      const float* got = p->scoreData();
      long differ = 0;
      for (size_t i = 0; i < want.size(); ++i) differ += got[i] != want[i];
      EXPECT_EQ(differ, 0) << c.what;
    }
    float top = 0;
    for (float v : want) top = std::max(top, v);
    EXPECT_GT(top, 0.0f) << c.what;
    EXPECT_GE(blobs[0].blobs.size(), 5u) << c.what;  // the robot's blobs and the ball
    ASSERT_EQ(blobs[0].blobs.size(), blobs[1].blobs.size()) << c.what;
  }
}

}  // namespace
}  // namespace dv
