// `dotvision calibrate` end to end: a Bayer frame and a field file in, the
// calibration, overlay and measures out; bad input exits 2 with one line and
// writes nothing; a failed quality gate exits 1 and writes nothing.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <nlohmann/json.hpp>
#include <sstream>

#include "calibration_scene.h"
#include "geometry/calibration/calibration_quality.h"
#include "geometry/calibration/point_pose.h"
#include "geometry/geometry_io.h"

namespace dv {
namespace {

namespace fs = std::filesystem;

struct CliRun {
  int code;
  std::string out;
};

CliRun runCli(const std::string& args) {
  const std::string cmd = std::string(DV_CLI_PATH) + " " + args + " 2>&1";
  FILE* p = popen(cmd.c_str(), "r");
  std::string out;
  char buf[512];
  while (p && fgets(buf, sizeof buf, p)) out += buf;
  const int status = p ? pclose(p) : -1;
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, out};
}

class CalibrateCli : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = fs::temp_directory_path() / ("dv_calib_cli_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
    field_ = FieldModel::divisionB();
    truth_ = testing::makeCamera(0, 1224, 1024, 725, -0.06, 611.5, 511.5, {-2250, 0, 4000}, kPi / 2, 0);
    const cv::Mat bgr = testing::renderFieldImage(truth_, field_);
    // RGGB mosaic, as a camera delivers it.
    cv::Mat bayer(bgr.rows, bgr.cols, CV_8UC1);
    for (int y = 0; y < bgr.rows; ++y)
      for (int x = 0; x < bgr.cols; ++x)
        bayer.at<uint8_t>(y, x) = bgr.at<cv::Vec3b>(y, x)[(y % 2 == 0) ? (x % 2 == 0 ? 2 : 1) : (x % 2 == 0 ? 1 : 0)];
    cv::imwrite((dir_ / "frame.pgm").string(), bayer);
    Geometry g;
    g.field = field_;
    g.cameras.push_back(truth_);  // must be ignored
    saveGeometry(g, (dir_ / "field.json").string());
    std::ostringstream c;
    const FieldRect r = *field_.cameraRegion(0, 2);
    const CameraModel cam(truth_);
    for (const auto& p : regionCornersCounterClockwise(r.x_min, r.x_max, r.y_min, r.y_max)) {
      const auto px = *cam.fieldToImage(p);
      c << (c.tellp() > 0 ? "," : "") << px.u << "," << px.v;
    }
    corners_ = c.str();
  }
  static void TearDownTestSuite() { fs::remove_all(dir_); }
  std::string base() const {
    return "calibrate --image " + (dir_ / "frame.pgm").string() + " --geometry " + (dir_ / "field.json").string() +
           " --camera-id 0 --num-cameras 2";
  }
  static inline fs::path dir_;
  static inline FieldModel field_;
  static inline CameraCalibration truth_;
  static inline std::string corners_;
};

TEST_F(CalibrateCli, CornersWriteCalibrationOverlayAndMeasures) {
  const auto out = dir_ / "calib.json";
  const auto r = runCli(base() + " --corners " + corners_ + " --camera-height 4000 --out " + out.string());
  ASSERT_EQ(r.code, 0) << r.out;
  EXPECT_NE(r.out.find("\"overlap_ratio\""), std::string::npos);
  EXPECT_NE(r.out.find("\"mean_distance_mm\""), std::string::npos);
  ASSERT_TRUE(fs::exists(out));
  EXPECT_TRUE(fs::exists(dir_ / "calib.overlay.png"));
  const Geometry g = loadGeometry(out.string());
  ASSERT_EQ(g.cameras.size(), 1u);
  const FieldRect area = field_.withBoundary();
  EXPECT_LE(meanFieldPositionError(truth_, g.cameras[0], 150, area, 32), 2.0);
}

TEST_F(CalibrateCli, BadOptionsExitTwoAndWriteNothing) {
  const auto out = dir_ / "bad.json";
  for (const std::string extra :
       {" --corners 1,2,3", " --corners 1,2,3,4,5,6,7,x", " --point 1,2=3", " --corners 10,10,20,20,9000,10,30,30",
        " --frobnicate 3", " --region x=0", " --near 1,2,3", " --region center --near 0,0"}) {
    const auto r = runCli(base() + extra + " --camera-height 4000 --out " + out.string());
    EXPECT_EQ(r.code, 2) << extra << ": " << r.out;
    EXPECT_FALSE(fs::exists(out)) << extra;
  }
  const auto missing = runCli("calibrate --image /nonexistent.pgm --geometry " + (dir_ / "field.json").string() +
                              " --camera-id 0 --out " + out.string());
  EXPECT_EQ(missing.code, 2);
  EXPECT_NE(missing.out.find("/nonexistent.pgm"), std::string::npos) << missing.out;
}

TEST_F(CalibrateCli, FailedGateExitsOneAndWritesNothing) {
  // Corners given in the wrong order describe a mirrored field.
  std::vector<std::string> parts;
  std::stringstream ss(corners_);
  for (std::string s; std::getline(ss, s, ',');) parts.push_back(s);
  const std::string swapped = parts[2] + "," + parts[3] + "," + parts[0] + "," + parts[1] + "," + parts[6] + "," +
                              parts[7] + "," + parts[4] + "," + parts[5];
  const auto out = dir_ / "gate.json";
  const auto r = runCli(base() + " --corners " + swapped + " --camera-height 4000 --out " + out.string());
  EXPECT_EQ(r.code, 1) << r.out;
  EXPECT_NE(r.out.find("no calibration written"), std::string::npos) << r.out;
  EXPECT_FALSE(fs::exists(out));
}

// Camera 0 of two by the layout covers x<0, but this one hangs over x>0, as
// with a venue that numbers its cameras differently.
class CalibrateCliOtherHalf : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = fs::temp_directory_path() / ("dv_calib_half_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
    field_ = FieldModel::divisionB();
    truth_ = testing::makeCamera(0, 1224, 1024, 725, 0.04, 611.5, 511.5, {2250, 0, 4000}, kPi / 2, 0);
    testing::SceneOptions so;
    so.robots = 4;
    cv::imwrite((dir_ / "frame.png").string(), testing::renderFieldImage(truth_, field_, so));
    Geometry g;
    g.field = field_;
    saveGeometry(g, (dir_ / "field.json").string());
  }
  static void TearDownTestSuite() { fs::remove_all(dir_); }
  static CliRun calibrate(const std::string& extra, const fs::path& out) {
    return runCli("calibrate --image " + (dir_ / "frame.png").string() + " --geometry " +
                  (dir_ / "field.json").string() + " --camera-id 0 --num-cameras 2 --camera-height 4000 --out " +
                  out.string() + extra);
  }
  static double error(const fs::path& out) {
    const Geometry g = loadGeometry(out.string());
    EXPECT_EQ(g.cameras.size(), 1u);
    return g.cameras.empty() ? 1e9 : meanFieldPositionError(truth_, g.cameras[0], 150, field_.withBoundary(), 32);
  }
  static inline fs::path dir_;
  static inline FieldModel field_;
  static inline CameraCalibration truth_;
};

TEST_F(CalibrateCliOtherHalf, RegionHintGivesTheRightHalfAndSaysSo) {
  const auto out = dir_ / "region.json";
  const auto r = calibrate(" --region 'x>0'", out);
  ASSERT_EQ(r.code, 0) << r.out;
  EXPECT_LE(error(out), 1.0);
  EXPECT_NE(r.out.find("field symmetry settled by --region x>0"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("alternative is a camera at (-22"), std::string::npos) << r.out;
}

TEST_F(CalibrateCliOtherHalf, NearHintGivesTheRightHalfAndTheReportSaysSo) {
  const auto out = dir_ / "near.json";
  const auto report = dir_ / "near.report.json";
  const auto r = calibrate(" --near 2500,300 --report " + report.string(), out);
  ASSERT_EQ(r.code, 0) << r.out;
  EXPECT_LE(error(out), 1.0);
  EXPECT_NE(r.out.find("settled by --near 2500,300"), std::string::npos) << r.out;
  std::ifstream f(report);
  const auto j = nlohmann::json::parse(f);
  EXPECT_TRUE(j["verdict"]["passed"].get<bool>());
  EXPECT_EQ(j["symmetry"]["basis"], "--near 2500,300");
  EXPECT_NEAR(j["symmetry"]["alternative_view_mm"][0].get<double>(), -2250, 50);
  EXPECT_NEAR(j["parameters"]["position_mm"][0].get<double>(), 2250, 20);
  // Lines found and used, each group with its model line and residual.
  EXPECT_GE(j["lines"]["groups_used"].get<int>(), 3);
  bool halfway = false;
  for (const auto& g : j["lines"]["groups"])
    if (g.value("line", "") == "HalfwayLine") halfway = g["mean_residual_px"].get<double>() < 1.0;
  EXPECT_TRUE(halfway) << j["lines"].dump();
}

// Without a hint the layout decides: the calibration lands on the other
// half, and the output says that the layout decided and what the
// alternative is.
TEST_F(CalibrateCliOtherHalf, WithoutHintTheLayoutDecidesAndNamesTheAlternative) {
  const auto out = dir_ / "layout.json";
  const auto r = calibrate("", out);
  ASSERT_EQ(r.code, 0) << r.out;
  EXPECT_NE(r.out.find("field symmetry settled by the camera-id layout (camera 0 of 2"), std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("alternative is a camera at (22"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("give --near 22"), std::string::npos) << r.out;
  EXPECT_GT(error(out), 1000);  // the twin, as the layout says
}

}  // namespace
}  // namespace dv
