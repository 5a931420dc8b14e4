// Differential tests of the OpenCL backend against the CPU reference, on
// whatever OpenCL device is installed (PoCL in CI): every stage on its own,
// whole frames (painted and rendered scenes, every input format and score
// kind), detections, bad frames, device selection and failures.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <string>

#include "core/error.h"
#include "detection/detector.h"
#include "pipeline/backend.h"
#include "pipeline/bayer_full.h"
#include "pipeline/bayer_sampling.h"
#include "pipeline/bayer_subsample.h"
#include "pipeline/cpu_pipeline.h"
#include "pipeline/kernels.h"
#include "pipeline/opencl/ocl_runtime.h"
#include "pipeline/opencl/opencl_pipeline.h"
#include "pipeline/remap_table.h"
#include "pipeline/thread_pool.h"
#include "pipeline/streak_score.h"
#include "pipeline/view_stretch.h"
#include "pipeline_test_scene.h"
#include "streak_test_scene.h"
#include "synth/renderer.h"
#include "synth/scene.h"

namespace dv {
namespace {

using test::addRobot;
using test::PaintedScene;
using test::topDownCamera;

// The first OpenCL device, looked up once for the whole binary.
const OclDeviceInfo* testDevice(std::string* why = nullptr) {
  static std::string reason;
  static const auto devices = listOpenClDevices(&reason);
  if (why) *why = reason;
  return devices.empty() ? nullptr : &devices.front();
}

#define DV_REQUIRE_OPENCL()                                                    \
  do {                                                                         \
    std::string why_;                                                          \
    if (!testDevice(&why_)) GTEST_SKIP() << "no OpenCL device here: " << why_; \
  } while (0)

PaintedScene robotScene() {
  PaintedScene s;
  const test::Color sides[4] = {test::kPink, test::kGreen, test::kGreen, test::kPink};
  addRobot(s, {820.3, 610.7}, 0.4, test::kYellow, sides);
  addRobot(s, {1170.9, 380.2}, -2.1, test::kBlue, sides);
  s.discs.push_back({{1150.4, 700.6}, 21.5, test::kOrange});
  // Faint discs (little chroma contrast to the carpet) around the ball,
  // within the weak reach of its blob, that score between the weak
  // threshold and the threshold: weak peaks on both backends.
  s.discs.push_back({{1215.2, 735.4}, 20, {46, 119, 52}});
  s.discs.push_back({{1095.7, 745.3}, 20, {52, 117, 61}});
  s.discs.push_back({{1150.6, 620.9}, 20, {49, 122, 54}});
  s.discs.push_back({{1185.1, 770.5}, 20, {56, 132, 56}});
  // A field line crossing, which must not become a blob on either backend.
  s.bands.push_back({{600, 300}, {1400, 300}, 10});
  s.bands.push_back({{1000, 100}, {1000, 900}, 10});
  return s;
}

// ~4 mm per grid cell: a 640x480 Bayer camera 2 m above the plane (or
// 320x240 BGR from 4 m, so that cells have the same size).
CameraModel smallCamera(BayerPattern bayer) {
  return bayer == BayerPattern::None ? topDownCamera(1000, 500, 150 + 4000, 1000, 320, 240)
                                     : topDownCamera(1000, 500, 150 + 2000, 1000, 640, 480);
}

// Each blob of `from` with a score clear of [lo, hi]'s ends (1e-3 relative,
// where the backends' sums may round either way) has a blob in `to` within
// 0.05 grid cells whose score agrees within 1e-3 relative and color within
// half a level; returns how many were compared.
int expectCounterparts(const std::vector<Blob>& from, const std::vector<Blob>& to, double lo, double hi,
                       const std::string& what) {
  int compared = 0;
  for (const auto& b : from) {
    if (std::abs(b.score - lo) <= 1e-3 * lo || std::abs(b.score - hi) <= 1e-3 * hi) continue;
    ++compared;
    const Blob* best = nullptr;
    double best_d = 1e9;
    for (const auto& c : to) {
      const double d = std::hypot(c.grid.x - b.grid.x, c.grid.y - b.grid.y);
      if (d < best_d) best_d = d, best = &c;
    }
    if (!best) {
      ADD_FAILURE() << what << ": no counterpart for the blob at " << b.grid.x << "," << b.grid.y;
      continue;
    }
    EXPECT_LE(best_d, 0.05) << what << ": blob at " << b.grid.x << "," << b.grid.y;
    EXPECT_LE(std::abs(best->score - b.score), 1e-3 * std::abs(best->score)) << what;
    EXPECT_EQ(best->streak, b.streak) << what;
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(best->rgb[c], b.rgb[c], 0.5) << what;
  }
  return compared;
}

// Blob lists agree: the same blobs, and the same weak peaks (either way, so
// none is missing on one side), apart from peaks whose ratio lies on a
// threshold within rounding.
void expectSameBlobs(const BlobList& cpu, const BlobList& ocl, const std::string& what,
                     const PipelineOptions& opt = PipelineOptions{}) {
  ASSERT_EQ(cpu.blobs.size(), ocl.blobs.size()) << what;
  expectCounterparts(ocl.blobs, cpu.blobs, 0, 1e9, what);
  const int a = expectCounterparts(cpu.weak, ocl.weak, opt.weak_threshold, opt.threshold, what + " (weak)");
  const int b = expectCounterparts(ocl.weak, cpu.weak, opt.weak_threshold, opt.threshold, what + " (weak)");
  EXPECT_EQ(a, b) << what;
  ASSERT_EQ(cpu.pale.size(), ocl.pale.size()) << what << " (pale)";
  expectCounterparts(ocl.pale, cpu.pale, 0, 1e9, what + " (pale)");
}

// The CPU reference the OpenCL backend matches: the full grid everywhere
// (the OpenCL backend has no coarse search).
PipelineOptions fullSearch(PipelineOptions opt) {
  opt.coarse_search = false;
  return opt;
}

// One frame through both backends built with `opt`: blob lists a (CPU) and
// b (OpenCL); ok() says whether both ran, error() why not.
struct BothBackends {
  BothBackends(const CameraModel& cam, const FieldModel& field, const PipelineOptions& opt, const cv::Mat& image)
      : cpu(cam, field, fullSearch(opt)), ocl(cam, field, opt, *testDevice()) {
    cpu_ok = cpu.process(image, a);
    ocl_ok = ocl.process(image, b);
  }
  bool ok() const { return cpu_ok && ocl_ok; }
  std::string error() const { return "cpu: " + cpu.lastError() + "; opencl: " + ocl.lastError(); }

  CpuPipeline cpu;
  OpenClPipeline ocl;
  BlobList a, b;
  bool cpu_ok = false, ocl_ok = false;
};

// The detector (no tracking) on both backends' blob lists: the same robots
// (team, id, position within 0.5 mm, orientation within 1e-3 rad) and balls
// (within 0.5 mm). `frame`: the image, for side slots without a blob (read
// from the frame alike for both). Returns the detections from the CPU's blobs.
Detections expectSameDetections(const CameraModel& cam, const FieldModel& field, const BlobList& cpu,
                                const BlobList& ocl, const FrameView& frame = {}) {
  DetectorOptions dopt;
  dopt.tracking = false;
  Detector da(cam, field, dopt), db(cam, field, dopt);
  Detections ra, rb;
  da.process(cpu, 0, ra, frame);
  db.process(ocl, 0, rb, frame);
  EXPECT_EQ(ra.robots.size(), rb.robots.size());
  EXPECT_EQ(ra.balls.size(), rb.balls.size());
  for (size_t i = 0; i < std::min(ra.robots.size(), rb.robots.size()); ++i) {
    EXPECT_EQ(ra.robots[i].team, rb.robots[i].team);
    EXPECT_EQ(ra.robots[i].id, rb.robots[i].id);
    EXPECT_NEAR(ra.robots[i].position.x, rb.robots[i].position.x, 0.5);
    EXPECT_NEAR(ra.robots[i].position.y, rb.robots[i].position.y, 0.5);
    EXPECT_NEAR(ra.robots[i].orientation, rb.robots[i].orientation, 1e-3);
  }
  for (size_t i = 0; i < std::min(ra.balls.size(), rb.balls.size()); ++i) {
    EXPECT_NEAR(ra.balls[i].position.x, rb.balls[i].position.x, 0.5);
    EXPECT_NEAR(ra.balls[i].position.y, rb.balls[i].position.y, 0.5);
  }
  return ra;
}

TEST(OpenClRuntime, ListsDevicesAndNamesThemWhenNothingMatches) {
  DV_REQUIRE_OPENCL();
  const auto devices = listOpenClDevices();
  const std::string list = describeOpenClDevices(devices);
  EXPECT_NE(list.find("platform 0"), std::string::npos) << list;
  EXPECT_NE(list.find(devices.front().device_name), std::string::npos) << list;
  try {
    selectOpenClDevice({"", "no-such-device-anywhere", false});
    FAIL() << "a device that does not exist was selected";
  } catch (const OclError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("no-such-device-anywhere"), std::string::npos) << what;
    EXPECT_NE(what.find(devices.front().device_name), std::string::npos) << what;
  }
  // Selection by index and by name finds the same device.
  const auto by_index = selectOpenClDevice({"0", "0", false});
  const auto by_name = selectOpenClDevice({"", devices.front().device_name.substr(0, 6), false});
  EXPECT_EQ(by_index.device_name, devices.front().device_name);
  EXPECT_EQ(by_name.device_name, devices.front().device_name);
}

TEST(OpenClRuntime, KernelBuildFailureIsReportedWithTheBuildLog) {
  DV_REQUIRE_OPENCL();
  try {
    OclContext ctx(*testDevice(), "-DDV_TEST_BUILD_FAILURE");
    FAIL() << "the program built although a test asked for a failure";
  } catch (const OclError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("build failed"), std::string::npos) << what;
    EXPECT_NE(what.find("DV_TEST_BUILD_FAILURE"), std::string::npos) << what;
  }
}

TEST(OpenClRuntime, ProgramBinaryIsCachedOnDisk) {
  DV_REQUIRE_OPENCL();
  const std::string dir = std::string(DV_BINARY_DIR) + "/opencl_cache_test";
  std::filesystem::remove_all(dir);
  const char* old = std::getenv("DV_OPENCL_CACHE");
  const std::string saved = old ? old : "";
  setenv("DV_OPENCL_CACHE", dir.c_str(), 1);
  {
    OclContext first(*testDevice());
    EXPECT_FALSE(first.programFromCache());
    OclContext second(*testDevice());
    EXPECT_TRUE(second.programFromCache());
  }
  EXPECT_FALSE(std::filesystem::is_empty(dir));
  if (old) setenv("DV_OPENCL_CACHE", saved.c_str(), 1);
  else unsetenv("DV_OPENCL_CACHE");
}

// Each stage of the OpenCL engine against the CPU reference's function for
// that stage, fed with the OpenCL engine's own input of that stage, so a
// difference points at one kernel.
TEST(OpenClStages, EveryStageMatchesTheCpuFunction) {
  DV_REQUIRE_OPENCL();
  const auto cam = smallCamera(BayerPattern::RGGB);
  const auto field = FieldModel::divisionB();
  PaintedScene scene = robotScene();
  scene.noise_sigma = 2;
  const cv::Mat raw = scene.render(cam, BayerPattern::RGGB);
  PipelineOptions opt;
  CpuPipeline cpu(cam, field, fullSearch(opt));
  OpenClPipeline ocl(cam, field, opt, *testDevice());
  BlobList cpu_blobs, ocl_blobs;
  ASSERT_TRUE(cpu.process(raw, cpu_blobs)) << cpu.lastError();
  ASSERT_TRUE(ocl.process(raw, ocl_blobs)) << ocl.lastError();
  const auto& e = ocl.engine();
  const auto& cfg = e.config();
  const int w = cfg.grid_width, h = cfg.grid_height;
  ASSERT_EQ(w, cpu.grid().width);
  ASSERT_EQ(h, cpu.grid().height);
  EXPECT_DOUBLE_EQ(ocl.gradientScale(), cpu.gradientScale());
  EXPECT_EQ(ocl.quadrantRadius(), cpu.quadrantRadius());

  // 1. Bayer subsampling to packed chroma (integer): exact where the grid reads.
  const int ws = raw.cols / 2, hs = raw.rows / 2;
  ThreadPool pool(1);
  RemapTable table;
  table.build(cam, cpu.grid(), opt.plane_height, SampleLattice{2, 0.5}, pool);
  EXPECT_TRUE(table.index == cfg.remap_index && table.frac == cfg.remap_frac);
  EXPECT_EQ(cfg.region_x_begin, table.x_begin);
  EXPECT_EQ(cfg.region_y_end, table.y_end);
  ChromaFixed fixed{};
  for (int i = 0; i < 3; ++i) fixed.a[i] = cfg.chroma_a[i], fixed.b[i] = cfg.chroma_b[i];
  const ChromaTransform t = ChromaTransform::of(opt.color);
  EXPECT_EQ(fixed.a[0], static_cast<int>(std::lround(t.a[0] * 1024)));
  std::vector<uint32_t> packed(static_cast<size_t>(ws) * hs, 0);
  bayerChromaRows(raw, BayerPattern::RGGB, fixed, packed.data(), table.y_begin, table.y_end, table.x_begin,
                  table.x_end);
  const auto opacked = e.readPackedChroma();
  long packed_diff = 0;
  for (int y = table.y_begin; y < table.y_end; ++y)
    for (int x = table.x_begin; x < table.x_end; ++x)
      packed_diff += opacked[static_cast<size_t>(y) * ws + x] != packed[static_cast<size_t>(y) * ws + x];
  EXPECT_EQ(packed_diff, 0) << "Bayer subsampling / packed chroma differs";

  // Frame brightness as the CPU reference measures it (raw Bayer sites).
  uint64_t sum = 0, n = 0;
  for (int y = table.y_begin; y < table.y_end; y += 16) {
    const uint8_t* r0 = raw.ptr<uint8_t>(2 * y);
    const uint8_t* r1 = raw.ptr<uint8_t>(2 * y + 1);
    for (int x = table.x_begin; x < table.x_end; x += 4) {
      const int all = r0[2 * x] + r0[2 * x + 1] + r1[2 * x] + r1[2 * x + 1];
      const int r = r0[2 * x], b = r1[2 * x + 1];  // RGGB
      sum += 2 * (r + b) + (all - r - b), n += 6;
    }
  }
  const float luma_mean = static_cast<float>(sum) / std::max<uint64_t>(1, n) + 1.0f;
  EXPECT_EQ(e.lastLumaMean(), luma_mean);

  // 2. Rectification of the OpenCL packed chroma: the same float operations
  // in the same order.
  std::vector<float> ca(static_cast<size_t>(w) * h), cb(ca.size());
  rectifyChromaRows(table, opacked.data(), 1.0f / (luma_mean * kPackedChromaScale), ca.data(), cb.data(), 0,
                    h);
  const auto chroma = e.readChroma();
  float worst = 0;
  for (size_t i = 0; i < ca.size(); ++i)
    worst = std::max({worst, std::abs(chroma[2 * i] - ca[i]), std::abs(chroma[2 * i + 1] - cb[i])});
  EXPECT_LE(worst, 1e-6f) << "chroma planes differ";

  // 3. Gradient dot product from the OpenCL chroma planes: fixed point, at
  // most one unit apart.
  std::vector<float> oa(ca.size()), ob(ca.size());
  for (size_t i = 0; i < ca.size(); ++i) oa[i] = chroma[2 * i], ob[i] = chroma[2 * i + 1];
  std::vector<int32_t> g(ca.size());
  gradientDotRows(oa.data(), ob.data(), w, h, cpu.gradientScale(), g.data(), 0, h);
  const auto og = e.readGradient();
  int32_t gworst = 0;
  for (size_t i = 0; i < g.size(); ++i) gworst = std::max(gworst, std::abs(og[i] - g[i]));
  EXPECT_LE(gworst, 1) << "gradient differs";

  // 4. Summed-area table from the OpenCL gradient: integer, exact.
  std::vector<uint32_t> sat((w + 1ull) * (h + 1ull), 0);
  satRowPrefixRows(og.data(), w, h, sat.data(), 0, h);
  satColumnPrefix(sat.data(), w, h, 0, w + 1);
  EXPECT_TRUE(e.readSat() == sat) << "summed-area table differs";

  // 5. Score from the table: exact; and against the CPU pipeline's own plane.
  std::vector<float> score(ca.size());
  quadrantMinScoreRows(sat.data(), w, h, cfg.quadrant_radius, cfg.inner_corner, score.data(), 0, h);
  const auto os = e.readScore();
  EXPECT_TRUE(os == score) << "blob score differs";
  const float* cpu_score = cpu.scoreData();
  float sworst = 0, smax = 0;
  for (size_t i = 0; i < os.size(); ++i)
    sworst = std::max(sworst, std::abs(os[i] - cpu_score[i])), smax = std::max(smax, std::abs(cpu_score[i]));
  EXPECT_LE(sworst, 1e-4f * smax) << "score plane differs from the CPU pipeline's";

  // 6. Peaks: the whole-frame blob lists.
  EXPECT_GE(cpu_blobs.blobs.size(), 11u);  // 10 pattern blobs and the ball
  EXPECT_GE(cpu_blobs.weak.size(), 1u);    // faint discs
  expectSameBlobs(cpu_blobs, ocl_blobs, "robot scene");
}

// Full Bayer sampling: the first stage (packed chroma and frame brightness)
// exactly as the CPU function, on a camera whose 2x2 cells are coarse enough
// that auto picks it; the rest of the pipeline is shared with subsampling.
TEST(OpenClStages, FullBayerSamplingMatchesTheCpuFunction) {
  DV_REQUIRE_OPENCL();
  const auto cam = topDownCamera(1000, 500, 150 + 5000, 1000, 640, 480);
  const auto field = FieldModel::divisionB();
  PaintedScene scene = robotScene();
  scene.noise_sigma = 2;
  const cv::Mat raw = scene.render(cam, BayerPattern::GRBG);
  PipelineOptions opt;
  opt.bayer = BayerPattern::GRBG;
  CpuPipeline cpu(cam, field, fullSearch(opt));
  OpenClPipeline ocl(cam, field, opt, *testDevice());
  ASSERT_EQ(cpu.options().bayer_sampling, BayerSampling::Full) << cpu.samplingNote();
  ASSERT_EQ(ocl.options().bayer_sampling, BayerSampling::Full);
  EXPECT_EQ(cpu.samplingNote(), ocl.samplingNote());
  BlobList cpu_blobs, ocl_blobs;
  ASSERT_TRUE(cpu.process(raw, cpu_blobs)) << cpu.lastError();
  ASSERT_TRUE(ocl.process(raw, ocl_blobs)) << ocl.lastError();
  const auto& e = ocl.engine();
  const auto& cfg = e.config();
  EXPECT_TRUE(cfg.full_bayer);
  ThreadPool pool(1);
  RemapTable table;
  table.build(cam, cpu.grid(), opt.plane_height, sampleLattice(cpu.options()), pool);
  EXPECT_EQ(table.src_width, raw.cols);
  EXPECT_TRUE(table.index == cfg.remap_index && table.frac == cfg.remap_frac);
  ChromaFixed fixed{};
  for (int i = 0; i < 3; ++i) fixed.a[i] = cfg.chroma_a[i], fixed.b[i] = cfg.chroma_b[i];
  std::vector<uint32_t> packed(static_cast<size_t>(raw.cols) * raw.rows, 0);
  fullBayerChromaRows(raw, opt.bayer, fixed, packed.data(), table.y_begin, table.y_end, table.x_begin,
                      table.x_end);
  const auto opacked = e.readPackedChroma();
  long diff = 0;
  for (int y = table.y_begin; y < table.y_end; ++y)
    for (int x = table.x_begin; x < table.x_end; ++x)
      diff += opacked[static_cast<size_t>(y) * raw.cols + x] != packed[static_cast<size_t>(y) * raw.cols + x];
  EXPECT_EQ(diff, 0) << "full Bayer sampling / packed chroma differs";
  // Brightness over the 2x2 cells under the samples read.
  const SampleRegion cells = fullBayerCells({table.x_begin, table.x_end, table.y_begin, table.y_end});
  const auto s = bayerSites(opt.bayer);
  uint64_t sum = 0, n = 0;
  for (int y = cells.y_begin; y < cells.y_end; y += 16)
    for (int x = cells.x_begin; x < cells.x_end; x += 4) {
      const int all = raw.at<uint8_t>(2 * y, 2 * x) + raw.at<uint8_t>(2 * y, 2 * x + 1) +
                      raw.at<uint8_t>(2 * y + 1, 2 * x) + raw.at<uint8_t>(2 * y + 1, 2 * x + 1);
      const int r = raw.at<uint8_t>(2 * y + s.ry, 2 * x + s.rx), b = raw.at<uint8_t>(2 * y + s.by, 2 * x + s.bx);
      sum += 2 * (r + b) + (all - r - b), n += 6;
    }
  EXPECT_EQ(e.lastLumaMean(), static_cast<float>(sum) / std::max<uint64_t>(1, n) + 1.0f);
  EXPECT_GE(cpu_blobs.blobs.size(), 9u);  // 5 mm pixels: most of the 11 blobs
  expectSameBlobs(cpu_blobs, ocl_blobs, "full Bayer sampling");
}

struct FrameCase {
  const char* name;
  BayerPattern bayer;
  ColorSpace color;
  BlobScoreKind score;
  double gain;
  double noise;
  BayerSampling sampling = BayerSampling::Auto;
};

class OpenClFrames : public ::testing::TestWithParam<FrameCase> {};

TEST_P(OpenClFrames, BlobsMatchTheCpuReference) {
  DV_REQUIRE_OPENCL();
  const auto& p = GetParam();
  const auto cam = smallCamera(p.bayer);
  const auto field = FieldModel::divisionB();
  PaintedScene scene = robotScene();
  scene.gain = p.gain;
  scene.noise_sigma = p.noise;
  const cv::Mat raw = scene.render(cam, p.bayer);
  PipelineOptions opt;
  opt.bayer = p.bayer;
  opt.color = p.color;
  opt.score = p.score;
  opt.bayer_sampling = p.sampling;
  CpuPipeline cpu(cam, field, fullSearch(opt));
  OpenClPipeline ocl(cam, field, opt, *testDevice());
  for (int frame = 0; frame < 2; ++frame) {  // buffers are reused: a second frame must agree too
    BlobList a, b;
    ASSERT_TRUE(cpu.process(raw, a)) << cpu.lastError();
    ASSERT_TRUE(ocl.process(raw, b)) << ocl.lastError();
    EXPECT_GE(a.blobs.size(), 5u) << p.name;
    EXPECT_GE(a.weak.size(), 1u) << p.name;  // a faint disc
    expectSameBlobs(a, b, p.name);
  }
}

INSTANTIATE_TEST_SUITE_P(
    Variants, OpenClFrames,
    ::testing::Values(FrameCase{"rggb_drgb_quadrant", BayerPattern::RGGB, ColorSpace::DRGB, BlobScoreKind::QuadrantMin, 1, 1.5},
                      FrameCase{"bggr_yuv_quadrant_dark", BayerPattern::BGGR, ColorSpace::YUV, BlobScoreKind::QuadrantMin, 0.4, 1},
                      FrameCase{"grbg_drgb_circle", BayerPattern::GRBG, ColorSpace::DRGB, BlobScoreKind::CircleMin, 1, 1},
                      FrameCase{"bgr_drgb_quadrant", BayerPattern::None, ColorSpace::DRGB, BlobScoreKind::QuadrantMin, 1, 1},
                      FrameCase{"bgr_yuv_circle", BayerPattern::None, ColorSpace::YUV, BlobScoreKind::CircleMin, 1.2, 0},
                      FrameCase{"rggb_full_drgb_quadrant", BayerPattern::RGGB, ColorSpace::DRGB, BlobScoreKind::QuadrantMin, 1, 1.5, BayerSampling::Full},
                      FrameCase{"gbrg_full_yuv_circle_dark", BayerPattern::GBRG, ColorSpace::YUV, BlobScoreKind::CircleMin, 0.5, 1, BayerSampling::Full}),
    [](const auto& info) { return std::string(info.param.name); });

// Where a fast ball is expected, a faint disc far from every blob is a weak
// peak on both backends, the same one.
TEST(OpenClFrames, AFaintDiscWhereAFastBallIsExpectedIsTheSameWeakPeak) {
  DV_REQUIRE_OPENCL();
  const auto cam = smallCamera(BayerPattern::RGGB);
  const auto field = FieldModel::divisionB();
  PaintedScene scene;
  const FieldMm far{1400.2, 820.7};
  scene.discs.push_back({{800.3, 500.6}, 21.5, test::kOrange});
  scene.discs.push_back({far, 20, {47, 119, 54}});
  const cv::Mat raw = scene.render(cam, BayerPattern::RGGB);
  PipelineOptions opt;
  CpuPipeline cpu(cam, field, fullSearch(opt));
  OpenClPipeline ocl(cam, field, opt, *testDevice());
  ExpectedPlaces expected;
  expected.at[expected.n++] = {far.x - 25, far.y + 30};
  cpu.expect(expected);
  ocl.expect(expected);
  BlobList a, b;
  ASSERT_TRUE(cpu.process(raw, a)) << cpu.lastError();
  ASSERT_TRUE(ocl.process(raw, b)) << ocl.lastError();
  int hits = 0;
  for (const auto& w : b.weak) hits += std::hypot(w.position.x - far.x, w.position.y - far.y) < 3;
  EXPECT_EQ(hits, 1);
  expectSameBlobs(a, b, "a faint disc where a fast ball is expected");
}

// A rendered scene (ray-cast renderer, carpet texture, lighting, noise, lens
// blur) through both backends, and the detector on both blob lists.
TEST(OpenClScenes, RenderedSceneGivesTheSameBlobsAndDetections) {
  DV_REQUIRE_OPENCL();
  SceneSpec spec = defaultScene();
  spec.antialias = 1;
  spec.frames = 1;
  Renderer renderer(spec);
  const auto geo = renderer.geometry();
  const RenderedFrame frame = renderer.render(0, 0);
  const CameraModel cam(spec.cameras[0].calib);
  PipelineOptions opt;
  const BothBackends run(cam, spec.field, opt, frame.image);
  ASSERT_TRUE(run.ok()) << run.error();
  const BlobList &a = run.a, &b = run.b;
  EXPECT_GE(a.blobs.size(), 10u);
  EXPECT_GE(a.weak.size(), 5u);  // carpet texture and noise near blobs
  expectSameBlobs(a, b, "rendered scene");
  {
    // A weak capacity that binds: both keep the same strongest few.
    PipelineOptions capped = opt;
    capped.max_weak_blobs = 4;
    const BothBackends run4(cam, spec.field, capped, frame.image);
    ASSERT_TRUE(run4.ok()) << run4.error();
    EXPECT_LE(run4.a.weak.size(), 4u);
    EXPECT_GE(run4.a.weak.size(), 3u);  // one of the four may be a second maximum of a blob
    expectSameBlobs(run4.a, run4.b, "rendered scene, 4 weak peaks at most", capped);
  }

  const Detections ra = expectSameDetections(cam, spec.field, a, b, FrameView{&frame.image, opt.bayer});
  EXPECT_FALSE(ra.robots.empty());
}

// The side view (a camera 1.6 m high at the touch line): far blobs are
// stretched along the viewing direction and both backends whiten the
// gradient there (pipeline/view_stretch.h); the same blobs and robots.
TEST(OpenClScenes, SideViewWhitenedGradientMatchesTheCpuReference) {
  DV_REQUIRE_OPENCL();
  SceneSpec spec = presetScene("side_view");
  Renderer renderer(spec);
  const RenderedFrame frame = renderer.render(0, 0);
  const CameraModel cam(spec.cameras[0].calib);
  PipelineOptions opt;
  const BothBackends run(cam, spec.field, opt, frame.image);
  ASSERT_TRUE(gradientForms(cam, run.cpu.grid(), opt.plane_height).any);
  ASSERT_TRUE(run.ok()) << run.error();
  EXPECT_GE(run.a.blobs.size(), 40u);
  expectSameBlobs(run.a, run.b, "side view");
  EXPECT_GE(expectSameDetections(cam, spec.field, run.a, run.b, FrameView{&frame.image, opt.bayer}).robots.size(),
            10u);
}

// A ball at 6.5 m/s, a streak the round score misses: the fast-ball pass
// on both backends. Its coarse plane and score from the OpenCL chroma
// exactly as the CPU functions compute them, the same streak blob (refined
// position, color), and the same ball from the detector.
TEST(OpenClScenes, FastBallStreakMatchesTheCpuReference) {
  DV_REQUIRE_OPENCL();
  const SceneSpec spec = test::streakScene(6500, 0.5);
  Renderer renderer(spec);
  const RenderedFrame frame = renderer.render(test::kStreakFrame, 0);
  const CameraModel cam(spec.cameras[0].calib);
  PipelineOptions opt;
  const BothBackends run(cam, spec.field, opt, frame.image);
  ASSERT_TRUE(run.ok()) << run.error();
  const BlobList &a = run.a, &b = run.b;

  const auto& e = run.ocl.engine();
  const int w = e.config().grid_width, h = e.config().grid_height;
  const StreakWindows sw = streakWindows(run.cpu.grid().scale, w, h);
  EXPECT_EQ(e.config().streak_coarse_width, sw.coarse_width);
  EXPECT_EQ(e.config().streak_margin, sw.margin);
  const auto chroma = e.readChroma();
  std::vector<float> oa(static_cast<size_t>(w) * h), ob(oa.size());
  for (size_t i = 0; i < oa.size(); ++i) oa[i] = chroma[2 * i], ob[i] = chroma[2 * i + 1];
  const size_t coarse = static_cast<size_t>(sw.coarse_width) * sw.coarse_height;
  const size_t lattice = static_cast<size_t>(sw.lattice_width) * sw.lattice_height;
  std::vector<float> pairs(2 * coarse), score(lattice);
  std::vector<uint8_t> orientation(lattice);
  streakCoarseRows(oa.data(), ob.data(), w, sw, pairs.data(), 0, sw.coarse_height);
  streakScoreRows(pairs.data(), sw, e.lastStreakLevels(), score.data(), orientation.data(), 0, sw.lattice_height);
  EXPECT_TRUE(e.readStreakScore() == score) << "streak score differs";

  int streaks = 0;
  for (const auto& blob : a.blobs) streaks += blob.streak;
  EXPECT_EQ(streaks, 1);
  expectSameBlobs(a, b, "fast ball");

  const Detections ra = expectSameDetections(cam, spec.field, a, b);
  ASSERT_EQ(ra.balls.size(), 1u);
  const auto& truth = frame.truth.balls(0);
  EXPECT_LT(std::hypot(ra.balls[0].position.x - truth.x(), ra.balls[0].position.y - truth.y()), 5.0);
}

// A ball clipped pale in a sun patch under tungsten (2.3 times the light):
// its peak fails the color gate and is kept apart (BlobList::pale) by both
// backends and by the CPU's coarse search alike, and the detector finds it
// from either list.
TEST(OpenClScenes, APaleBallPeakIsKeptApartByEverySearch) {
  DV_REQUIRE_OPENCL();
  SceneSpec spec = presetScene("top_down_div_b_half");
  spec.lighting.white_balance = {1.6, 1.0, 0.6};
  spec.lighting.saturation = 0.8;
  spec.materials.yellow = {250, 165, 0};
  spec.materials.ball = {255, 150, 40};
  spec.lighting.sun_patches = {{{-1500, 700}, 700, 600, 0.0, 2.3, 0.2}};
  spec.ball.present = true;
  spec.ball.position = {-1500, 600, 21.5};
  Renderer renderer(spec);
  const RenderedFrame frame = renderer.render(0, 0);
  const CameraModel cam(spec.cameras[0].calib);
  PipelineOptions opt;
  const BothBackends run(cam, spec.field, opt, frame.image);
  ASSERT_TRUE(run.ok()) << run.error();
  expectSameBlobs(run.a, run.b, "pale ball");
  CpuPipeline coarse(cam, spec.field, opt);
  BlobList c;
  ASSERT_TRUE(coarse.process(frame.image, c)) << coarse.lastError();
  // On the rectification plane the ball lies about 25 mm out along its ray.
  for (const BlobList* list : {&run.a, &run.b, static_cast<const BlobList*>(&c)}) {
    int near = 0;
    for (const Blob& p : list->pale) near += std::hypot(p.position.x + 1500, p.position.y - 600) < 60;
    EXPECT_EQ(near, 1);
  }
  const Detections ra = expectSameDetections(cam, spec.field, run.a, run.b, FrameView{&frame.image, opt.bayer});
  ASSERT_EQ(ra.balls.size(), 1u);
  EXPECT_LT(std::hypot(ra.balls[0].position.x + 1500, ra.balls[0].position.y - 600), 3.0);
}

TEST(OpenClErrors, BadFramesAreRejectedWithTheCpuReferenceMessage) {
  DV_REQUIRE_OPENCL();
  const auto cam = smallCamera(BayerPattern::RGGB);
  const auto field = FieldModel::divisionB();
  CpuPipeline cpu(cam, field, {});
  OpenClPipeline ocl(cam, field, {}, *testDevice());
  const cv::Mat frames[] = {cv::Mat(), cv::Mat(100, 100, CV_8UC1, cv::Scalar(0)),
                            cv::Mat(480, 640, CV_16UC1, cv::Scalar(0)), cv::Mat(480, 640, CV_8UC3, cv::Scalar(0)),
                            cv::Mat(480, 640, CV_8UC4, cv::Scalar(0))};
  for (const auto& f : frames) {
    BlobList a, b;
    EXPECT_FALSE(cpu.process(f, a));
    EXPECT_FALSE(ocl.process(f, b));
    EXPECT_EQ(ocl.lastError(), cpu.lastError());
    EXPECT_TRUE(b.blobs.empty());
  }
  // A good frame after bad ones still works.
  BlobList b;
  EXPECT_TRUE(ocl.process(robotScene().render(cam, BayerPattern::RGGB), b)) << ocl.lastError();
  EXPECT_FALSE(b.blobs.empty());
}

TEST(OpenClErrors, CameraProblemsAreInputErrorsAsOnTheCpu) {
  DV_REQUIRE_OPENCL();
  const auto field = FieldModel::divisionB();
  const auto far_away = topDownCamera(20000, 20000, 3000, 1000, 640, 480);
  EXPECT_THROW(OpenClPipeline(far_away, field, {}, *testDevice()), InputError);
  auto calib = smallCamera(BayerPattern::RGGB).calibration();
  calib.image_width = 0;
  EXPECT_THROW(OpenClPipeline(CameraModel(calib), field, {}, *testDevice()), InputError);
}

TEST(OpenClBackend, ParsesBackendNames) {
  Backend b;
  EXPECT_TRUE(parseBackend("auto", b));
  EXPECT_EQ(b, Backend::Auto);
  EXPECT_TRUE(parseBackend("CPU", b));
  EXPECT_EQ(b, Backend::Cpu);
  EXPECT_TRUE(parseBackend("opencl", b));
  EXPECT_EQ(b, Backend::OpenCl);
  EXPECT_FALSE(parseBackend("cuda", b));
  EXPECT_FALSE(parseBackend(nullptr, b));
}

TEST(OpenClBackend, ChoiceFallbackAndErrors) {
  const auto cam = smallCamera(BayerPattern::RGGB);
  const auto field = FieldModel::divisionB();
  std::string why;
  auto cpu = makePipeline(cam, field, {}, {Backend::Cpu, "", ""}, &why);
  EXPECT_EQ(cpu->name(), "cpu");

  // auto: a GPU if there is one, never an OpenCL CPU device (PoCL is slower
  // than the CPU reference); the reason is given.
  auto devices = listOpenClDevices();
  const bool has_gpu = std::any_of(devices.begin(), devices.end(), [](const auto& d) { return d.is_gpu; });
  auto chosen = makePipeline(cam, field, {}, {Backend::Auto, "", ""}, &why);
  if (has_gpu) {
    EXPECT_EQ(chosen->name().rfind("opencl", 0), 0u) << why;
  } else {
    EXPECT_EQ(chosen->name(), "cpu");
    EXPECT_NE(why.find("CPU reference"), std::string::npos) << why;
  }

  // opencl with a device that does not exist: an InputError that lists what exists.
  try {
    makePipeline(cam, field, {}, {Backend::OpenCl, "", "no-such-device-anywhere"}, &why);
    FAIL() << "an unknown device was accepted";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("--backend opencl"), std::string::npos) << what;
    if (!devices.empty()) {
      EXPECT_NE(what.find(devices.front().device_name), std::string::npos) << what;
    }
  }
  // auto with an unknown device falls back to the CPU reference.
  auto fallback = makePipeline(cam, field, {}, {Backend::Auto, "", "no-such-device-anywhere"}, &why);
  EXPECT_EQ(fallback->name(), "cpu");

  if (!devices.empty()) {
    // opencl on the installed device (any type) works and finds blobs.
    auto ocl = makePipeline(cam, field, {}, {Backend::OpenCl, "0", "0"}, &why);
    EXPECT_EQ(ocl->name().rfind("opencl", 0), 0u);
    BlobList b;
    EXPECT_TRUE(ocl->process(robotScene().render(cam, BayerPattern::RGGB), b)) << ocl->lastError();
    EXPECT_GE(b.blobs.size(), 11u);
    EXPECT_GT(ocl->times().total_ms, 0);
  }
}

}  // namespace
}  // namespace dv
