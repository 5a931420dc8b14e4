// Bad input to the calibration gets one clear message and no calibration;
// and the building blocks do what the later steps rely on.
#include <gtest/gtest.h>

#include "calibration_scene.h"
#include "core/error.h"
#include "geometry/calibration/calibrate_camera.h"
#include "geometry/calibration/line_groups.h"
#include "geometry/calibration/line_pixels.h"
#include "io/image_decode.h"

namespace dv {
namespace {

CameraCalibration topDown() {
  return testing::makeCamera(0, 1224, 1024, 725, -0.06, 611.5, 511.5, {-2250, 0, 4000}, kPi / 2, 0);
}

CalibrationRequest cornersFor(const CameraCalibration& truth, const FieldModel& f) {
  CalibrationRequest req;
  req.camera_id = 0;
  req.num_cameras = 2;
  req.camera_height_mm = 4000;
  req.source = "test.png";
  const FieldRect r = *f.cameraRegion(0, 2);
  for (const auto& p : regionCornersCounterClockwise(r.x_min, r.x_max, r.y_min, r.y_max))
    req.points.push_back({p, *CameraModel(truth).fieldToImage(p)});
  return req;
}

std::string messageOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(CalibrationInput, ImageWithoutFieldIsRejectedWithItsName) {
  const FieldModel f = FieldModel::divisionB();
  cv::Mat grey(1024, 1224, CV_8UC3, cv::Scalar(90, 90, 90));
  cv::randn(grey, cv::Scalar(90, 90, 90), cv::Scalar(3, 3, 3));
  const std::string msg = messageOf([&] { calibrateCamera(grey, f, cornersFor(topDown(), f)); });
  EXPECT_NE(msg.find("test.png"), std::string::npos) << msg;
  EXPECT_NE(msg.find("no field lines"), std::string::npos) << msg;
}

TEST(CalibrationInput, CornersOutsideTheImageAreRejected) {
  const FieldModel f = FieldModel::divisionB();
  const cv::Mat img = testing::renderFieldImage(topDown(), f);
  auto req = cornersFor(topDown(), f);
  req.points[2].image.u = 5000;
  const std::string msg = messageOf([&] { calibrateCamera(img, f, req); });
  EXPECT_NE(msg.find("outside"), std::string::npos) << msg;
}

TEST(CalibrationInput, TooFewPointsAndUnknownCameraAreRejected) {
  const FieldModel f = FieldModel::divisionB();
  const cv::Mat img = testing::renderFieldImage(topDown(), f);
  auto req = cornersFor(topDown(), f);
  req.points.resize(3);
  EXPECT_NE(messageOf([&] { calibrateCamera(img, f, req); }).find("four or more"), std::string::npos);
  // The automatic mode needs the layout's region of an unknown camera id;
  // given points do not (they place the camera themselves).
  req = cornersFor(topDown(), f);
  req.camera_id = 7;
  EXPECT_EQ(messageOf([&] { calibrateCamera(img, f, req); }), "");
  req.points.clear();
  EXPECT_NE(messageOf([&] { calibrateCamera(img, f, req); }).find("camera id 7"), std::string::npos);
}

TEST(CalibrationInput, FieldWithoutLinesIsRejected) {
  FieldModel f = FieldModel::divisionB();
  const cv::Mat img = testing::renderFieldImage(topDown(), f);
  const auto req = cornersFor(topDown(), f);
  f.lines.clear();
  EXPECT_NE(messageOf([&] { calibrateCamera(img, f, req); }).find("no lines"), std::string::npos);
}

TEST(CalibrationInput, CorruptImageFormatsAreInputErrors) {
  EXPECT_THROW(toBgrImage(cv::Mat(), "x.png"), InputError);
  EXPECT_THROW(toBgrImage(cv::Mat(10, 10, CV_16UC1, cv::Scalar(0)), "x.png"), InputError);
  EXPECT_THROW(readImageFile("/nonexistent/dir/image.pgm"), InputError);
}

// Wrong corner clicks (a mirrored order) must not produce a calibration.
TEST(CalibrationInput, WrongCornerOrderFailsTheQualityGate) {
  const FieldModel f = FieldModel::divisionB();
  const cv::Mat img = testing::renderFieldImage(topDown(), f);
  auto req = cornersFor(topDown(), f);
  std::swap(req.points[0].image, req.points[1].image);
  std::swap(req.points[2].image, req.points[3].image);
  const auto out = calibrateCamera(img, f, req);
  ASSERT_TRUE(out.problem.has_value());
}

// Looking straight down, the height is not observable: without it the
// calibration is refused with a request for --camera-height.
TEST(CalibrationInput, StraightDownWithoutHeightAsksForIt) {
  const FieldModel f = FieldModel::divisionB();
  const cv::Mat img = testing::renderFieldImage(topDown(), f);
  auto req = cornersFor(topDown(), f);
  req.camera_height_mm.reset();
  const auto out = calibrateCamera(img, f, req);
  ASSERT_TRUE(out.problem.has_value());
  EXPECT_NE(out.problem->find("--camera-height"), std::string::npos) << *out.problem;
}

// A correct calibration passes the gate; the same one moved by 60 mm fails.
TEST(CalibrationQuality, GateSeparatesRightFromShifted) {
  const FieldModel f = FieldModel::divisionB();
  const CameraCalibration truth = topDown();
  const cv::Mat img = testing::renderFieldImage(truth, f);
  const FieldRect region = *f.cameraRegion(0, 2);
  const LineObservation obs = observeLines(img, f, region);
  QualityGateOptions g;
  g.region = region;
  const auto good = measureCalibration(truth, f, obs.pixels, obs.distance);
  EXPECT_FALSE(qualityProblem(truth, good, g)) << *qualityProblem(truth, good, g);
  EXPECT_GT(good.overlap_ratio, 0.9);
  EXPECT_LT(good.mean_distance_px, 1.0);
  CameraCalibration shifted = truth;
  shifted.tx += 60;
  const auto bad = measureCalibration(shifted, f, obs.pixels, obs.distance);
  EXPECT_TRUE(qualityProblem(shifted, bad, g));
  EXPECT_LT(bad.overlap_ratio, good.overlap_ratio);
}

// Thormählen grouping joins the two edges and the pieces of one line, keeps
// apart parallel lines 20 px apart and drops short segments.
TEST(CalibrationLines, GroupingFollowsThormaehlensRules) {
  std::vector<LineSegment> s = {
      {{0, 100}, {300, 100}},   {{0, 104}, {300, 104}},    // two edges of one line
      {{420, 101}, {800, 102}},                             // same line after a 120 px gap
      {{0, 124}, {300, 124}},                               // a parallel line 20 px away
      {{1000, 100}, {1300, 100}},                           // collinear but 200 px beyond
      {{50, 300}, {55, 300}},                               // too short
  };
  const auto groups = groupSegments(s);
  ASSERT_EQ(groups.size(), 3u);
  EXPECT_EQ(groups[0].segments.size(), 3u);
  EXPECT_NEAR(groups[0].extent_px, 800, 1);
}

// The ridge detector finds a thin bright line and ignores a wide bright area
// and a single edge.
TEST(CalibrationLines, RidgeDetectorKeepsThinLinesOnly) {
  cv::Mat img(200, 200, CV_8UC3, cv::Scalar(50, 110, 40));
  cv::line(img, {20, 50}, {180, 50}, cv::Scalar(220, 220, 220), 3);
  cv::rectangle(img, {20, 100}, {180, 140}, cv::Scalar(220, 220, 220), cv::FILLED);  // wide
  LinePixelOptions o;
  o.half_width_px = 3;
  const cv::Mat mask = detectLinePixels(img, o);
  EXPECT_GT(cv::countNonZero(mask.rowRange(48, 53)), 150);  // along its 160 px
  EXPECT_EQ(cv::countNonZero(mask.rowRange(95, 145)), 0);
}

TEST(CalibrationLines, DistortionAndPrincipalPointFromStraightLines) {
  const FieldModel f = FieldModel::divisionA();
  const CameraCalibration truth =
      testing::makeCamera(3, 1224, 1024, 900, 0.25, 631.5, 511.5, {3000, 2250, 5000}, 0.1, 0);
  const cv::Mat img = testing::renderFieldImage(truth, f);
  const LineObservation obs = observeLines(img, f, *f.cameraRegion(3, 4));
  IntrinsicsOptions io;
  io.min_group_extent_px = 512;
  const auto r = calibrateDistortion(obs.groups, 1224, 1024, io);
  ASSERT_TRUE(r);
  EXPECT_LT(r->rms_px, r->rms_before_px);
  EXPECT_NEAR(r->distortion.k(truth.focal_length), 0.25, 0.02);
  EXPECT_NEAR(r->distortion.cx, 631.5, 6);
  EXPECT_NEAR(r->distortion.cy, 511.5, 6);
}

}  // namespace
}  // namespace dv
