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

}  // namespace
}  // namespace dv
