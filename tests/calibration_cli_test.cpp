// `dotvision calibrate` end to end: a Bayer frame and a field file in, the
// calibration, overlay and measures out; bad input exits 2 with one line and
// writes nothing; a failed quality gate exits 1 and writes nothing.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
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
        " --frobnicate 3"}) {
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

}  // namespace
}  // namespace dv
