// Four-point mode on drawn field images with the true calibration known: the
// quality bar is a mean field-position error of at most 2 mm over a grid of
// image pixels, at z = 0 and at z = 150 mm.
#include <gtest/gtest.h>

#include <random>

#include "calibration_scene.h"
#include "geometry/calibration/calibrate_camera.h"

namespace dv {
namespace {

using testing::makeCamera;
using testing::renderFieldImage;

struct Scenario {
  const char* name;
  FieldModel field;
  unsigned num_cameras;
  uint32_t camera_id;
  CameraCalibration truth;
  bool give_height;
};

std::vector<PointCorrespondence> cornerClicks(const CameraCalibration& truth, const FieldRect& r,
                                              double noise_px, unsigned seed) {
  const CameraModel cam(truth);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> n(-noise_px, noise_px);
  std::vector<PointCorrespondence> out;
  for (const auto& p : regionCornersCounterClockwise(r.x_min, r.x_max, r.y_min, r.y_max)) {
    const auto px = cam.fieldToImage(p);
    EXPECT_TRUE(px.has_value());
    out.push_back({p, {px->u + n(rng), px->v + n(rng)}});
  }
  return out;
}

double gridError(const Scenario& s, const CameraCalibration& estimate) {
  const FieldRect area = s.field.withBoundary();
  const double e0 = meanFieldPositionError(s.truth, estimate, 0, area, 32);
  const double e150 = meanFieldPositionError(s.truth, estimate, 150, area, 32);
  std::printf("[ %s ] mean field-position error: %.3f mm at z=0, %.3f mm at z=150\n", s.name, e0, e150);
  return std::max(e0, e150);
}

Scenario topDownPincushion() {
  const FieldModel f = FieldModel::divisionB();
  // Camera 0 of two sees x in [-4500, 0]; the image's long side runs along y.
  return {"top-down pincushion", f, 2, 0,
          makeCamera(0, 2448, 2048, 1450, -0.08, 1223.5, 1023.5, {-2250, 0, 4000}, kPi / 2, 0), true};
}

Scenario topDownBarrelOffCenter() {
  const FieldModel f = FieldModel::divisionA();
  return {"top-down strong barrel, principal point 40 px off", f, 4, 3,
          makeCamera(3, 2448, 2048, 1800, 0.25, 1263.5, 1023.5, {3000, 2250, 5000}, 0.1, 0.0), true};
}

TEST(CalibrationFourPoint, TopDownPincushionWithinTwoMillimetres) {
  const Scenario s = topDownPincushion();
  const cv::Mat img = renderFieldImage(s.truth, s.field);
  CalibrationRequest req;
  req.camera_id = s.camera_id;
  req.num_cameras = s.num_cameras;
  req.camera_height_mm = 4000;
  req.points = cornerClicks(s.truth, *s.field.cameraRegion(s.camera_id, s.num_cameras), 0, 1);
  const auto out = calibrateCamera(img, s.field, req);
  ASSERT_FALSE(out.problem) << *out.problem;
  EXPECT_LE(gridError(s, out.calibration), 2.0);
  EXPECT_GT(out.measures.overlap_ratio, 0.8);
}

TEST(CalibrationFourPoint, StrongBarrelOffCenterWithinTwoMillimetres) {
  const Scenario s = topDownBarrelOffCenter();
  const cv::Mat img = renderFieldImage(s.truth, s.field);
  CalibrationRequest req;
  req.camera_id = s.camera_id;
  req.num_cameras = s.num_cameras;
  req.camera_height_mm = 5000;
  req.points = cornerClicks(s.truth, *s.field.cameraRegion(s.camera_id, s.num_cameras), 0, 2);
  const auto out = calibrateCamera(img, s.field, req);
  ASSERT_FALSE(out.problem) << *out.problem;
  ASSERT_TRUE(out.intrinsics);
  std::printf("principal point %.1f %.1f (true %.1f %.1f), k %.4f (true %.4f)\n",
              out.calibration.principal_point_x, out.calibration.principal_point_y,
              s.truth.principal_point_x, s.truth.principal_point_y, out.calibration.distortion,
              s.truth.distortion);
  EXPECT_LE(gridError(s, out.calibration), 2.0);
}

// Line crossings of the field that the true camera sees well inside the image.
std::vector<PointCorrespondence> visibleCrossings(const CameraCalibration& truth, const FieldModel& f,
                                                  double noise_px, unsigned seed) {
  const double l = f.field_length / 2.0, w = f.field_width / 2.0;
  const double xp = l - f.penalty_area_depth, yp = f.penalty_area_width / 2.0;
  const CameraModel cam(truth);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> n(-noise_px, noise_px);
  std::vector<PointCorrespondence> out;
  for (double x : {-l, -xp, 0.0, xp, l})
    for (double y : {-w, -yp, 0.0, yp, w}) {
      const auto px = cam.fieldToImage({x, y, 0});
      if (!px || px->u < 50 || px->v < 50 || px->u > truth.image_width - 50 || px->v > truth.image_height - 50)
        continue;
      out.push_back({{x, y, 0}, {px->u + n(rng), px->v + n(rng)}});
    }
  return out;
}

Scenario sideView() {
  const FieldModel f = FieldModel::divisionB();
  // At the bottom touch line, 400 mm outside it, 3.5 m up, tilted 45 degrees
  // towards the field.
  return {"side view from the field edge", f, 2, 0,
          makeCamera(0, 2448, 2048, 1700, -0.05, 1223.5, 1023.5, {-2250, -3400, 3500}, 0, kPi / 4), false};
}

TEST(CalibrationFourPoint, SideViewWithinTwoMillimetres) {
  const Scenario s = sideView();
  const cv::Mat img = renderFieldImage(s.truth, s.field);
  CalibrationRequest req;
  req.camera_id = s.camera_id;
  req.num_cameras = s.num_cameras;
  req.points = visibleCrossings(s.truth, s.field, 0, 3);
  ASSERT_GE(req.points.size(), 4u);
  const auto out = calibrateCamera(img, s.field, req);
  ASSERT_FALSE(out.problem) << *out.problem;
  EXPECT_LE(gridError(s, out.calibration), 2.0);
}

// With clicks off by up to 2 px the line refinement must still land within
// the bar; the clicks alone would not.
TEST(CalibrationFourPoint, NoisyClicksAreCorrectedByTheLines) {
  const Scenario s = topDownPincushion();
  testing::SceneOptions so;
  so.robots = 8;
  const cv::Mat img = renderFieldImage(s.truth, s.field, so);
  CalibrationRequest req;
  req.camera_id = s.camera_id;
  req.num_cameras = s.num_cameras;
  req.camera_height_mm = 4000;
  req.points = cornerClicks(s.truth, *s.field.cameraRegion(s.camera_id, s.num_cameras), 2.0, 7);
  const auto out = calibrateCamera(img, s.field, req);
  ASSERT_FALSE(out.problem) << *out.problem;
  EXPECT_TRUE(out.refinement_accepted);
  EXPECT_LE(gridError(s, out.calibration), 2.0);
}

}  // namespace
}  // namespace dv
